#!/usr/bin/env bash
# Disorder sweep (a benchmark figure, not a test): 2D anti-plane plates of 16 x 16
# particles on the periodic unit square, cubic MLS, D = 2, lumped mass, perturbed by
# F = 0, 0.05, ..., 0.40 of the spacing, SEEDS seeds each (default 20), for nodal
# integration and the stress points stress-quad and stress-tri: min / median / max over
# the seeds of lambda_max dx^2 / c^2, of the zero-mode count and of the quadrature points
# with some phi_I <= 0, and the models with a lumped mass <= 0
# (mfstab eigs --perturb F --seeds N --zero-modes).
#   analysis/bench/disorder.sh [BUILD_DIR]
# writes notebooks-data/disorder.csv and, with Debian's python3-matplotlib,
# notebooks-data/disorder.png.
# CSV: quadrature,perturb,seeds,lambda_max_min_norm,lambda_max_median_norm,lambda_max_max_norm (dx^2/c^2),
#      zero_modes_min,zero_modes_median,zero_modes_max,negative_phi_min,negative_phi_median,
#      negative_phi_max,nonpositive_mass_models
set -euo pipefail
BUILD=${1:-build}
M=$BUILD/tools/mfstab
SEEDS=${SEEDS:-20}
OUT=${OUT:-notebooks-data/disorder.csv}
[ -x "$M" ] || { echo "disorder.sh: $M not found (build first)" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/disorder.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$OUT")"
echo "quadrature,perturb,seeds,lambda_max_min_norm,lambda_max_median_norm,lambda_max_max_norm,zero_modes_min,zero_modes_median,zero_modes_max,negative_phi_min,negative_phi_median,negative_phi_max,nonpositive_mass_models" >"$work/out.csv"
dx2=$(awk 'BEGIN { printf "%.17g", (1 / 16) ^ 2 }')
for q in nodal stress-quad stress-tri; do
  for F in 0 0.05 0.10 0.15 0.20 0.25 0.30 0.35 0.40; do
    if [ "$F" = 0 ]; then
      "$M" eigs --dim 2 --nodes 16,16 --periodic --quadrature $q --zero-modes -o "$work/r.csv"
      awk -F, -v q=$q -v d="$dx2" 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i }
        NR == 2 { l = $h["lambda_max_per_s2"] * d; z = $h["zero_modes"]; n = $h["negative_phi_points"]
          printf "%s,0,1,%.10g,%.10g,%.10g,%s,%s,%s,%s,%s,%s,%d\n", q, l, l, l, z, z, z, n, n, n, ($h["nonpositive_masses"] > 0 ? 1 : 0) }' \
        "$work/r.csv" >>"$work/out.csv"
    else
      "$M" eigs --dim 2 --nodes 16,16 --periodic --quadrature $q --zero-modes --perturb "$F" --seeds "$SEEDS" \
        -o "$work/r.csv" 2>/dev/null
      awk -F, -v q=$q -v F="$F" -v d="$dx2" 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i }
        NR == 2 { f = "%.10g"; printf "%s,%s,%s," f "," f "," f ",%s,%s,%s,%s,%s,%s,%s\n", q, F, $h["seeds"],
          $h["lambda_max_min_per_s2"] * d, $h["lambda_max_median_per_s2"] * d, $h["lambda_max_max_per_s2"] * d,
          $h["zero_modes_min"], $h["zero_modes_median"], $h["zero_modes_max"], $h["negative_phi_min"],
          $h["negative_phi_median"], $h["negative_phi_max"], $h["nonpositive_mass_models"] }' \
        "$work/r.csv" >>"$work/out.csv"
    fi
  done
done
mv "$work/out.csv" "$OUT"
echo "wrote $OUT" >&2
PY=/usr/bin/python3
if $PY -c 'import matplotlib' 2>/dev/null; then
  $PY - "$OUT" "${OUT%.csv}.png" <<'EOF'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
fig, ax = plt.subplots(1, 3, figsize=(13, 4))
style = {"nodal": ("C0", "o", "-"), "stress-quad": ("C1", "s", "--"), "stress-tri": ("C2", "^", ":")}
for q, (c, m, ls) in style.items():
    r = [x for x in rows if x["quadrature"] == q]
    F = [100 * float(x["perturb"]) for x in r]
    for a, key in zip(ax, ["lambda_max", "zero_modes", "negative_phi"]):
        u = "_norm" if key == "lambda_max" else ""
        lo = [float(x[key + "_min" + u]) for x in r]
        md = [float(x[key + "_median" + u]) for x in r]
        hi = [float(x[key + "_max" + u]) for x in r]
        a.plot(F, md, color=c, marker=m, ls=ls, label=q + " (median)")
        a.fill_between(F, lo, hi, color=c, alpha=0.15)
ax[0].set_ylabel(r"$\lambda_{max}\,dx^2/c^2$ (normalized)")
ax[1].set_ylabel(r"zero-energy modes ($\lambda \leq 10^{-8} \lambda_{max}$, rigid included)")
ax[2].set_ylabel(r"quadrature points with some $\phi_I \leq 0$")
for a in ax:
    a.set_xlabel("perturbation F (% of dx)")
    a.grid(alpha=0.3)
ax[0].legend(fontsize=8)
n = rows[-1]["seeds"]
fig.suptitle("Disorder: 16 x 16 periodic anti-plane plate, cubic MLS, D = 2, lumped mass; "
             f"min-max band over {n} seeds (mfstab eigs --perturb F --seeds {n})", fontsize=10)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
EOF
  echo "wrote ${OUT%.csv}.png" >&2
fi
