#!/usr/bin/python3
"""The summary of analysis/bench/run.sh: for every benchmark CSV in DIR with
limit_kind and fraction columns (limits.py), the fraction of its physical
limit each kind of row reaches (median over the rows of that kind, the bar;
min and max, the whisker), on a log scale; bytes-limited rows blue,
flop-limited orange.  Rows without a limit (limit_kind none) and the
min/median/max summary rows of a CSV with runs are not shown; a second
fraction of the same rows (EXTRA: numpy_fraction, cd1_fraction) is a bar
of its own, its label suffixed.

    summary_plot.py DIR OUT.png
"""
import csv
import glob
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABEL_COLS = ("tool", "phase", "case", "method", "kernel", "scheme", "blas", "frame", "family",
              "comparison", "command", "scene", "rule", "kind", "pages")
# a second fraction of the same rows (limits.py): its own bar, labelled by the suffix
EXTRA = {"dispersion_numpy": (("numpy_fraction", "numpy"),),
         "table4": (("cd1_fraction", "cd1"),)}


def groups(path):
    name = os.path.splitext(os.path.basename(path))[0].replace("bench_", "")
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(l for l in fh if not l.startswith("#")))
    out = {}
    for r in rows:
        kind = r.get("limit_kind", "")
        if kind not in ("bytes", "flops") or r.get("run") in ("min", "median", "max"):
            continue  # no limit, or a summary row of the runs
        parts = [r[c] for c in LABEL_COLS if r.get(c)]
        if r.get("threads"):
            parts.append(f"{r['threads']}t")
        if r.get("ranks"):
            parts.append(f"{r['ranks']}r")
        label = (f"{name}: " + " ".join(parts)).strip()
        for col, suffix in (("fraction", ""),) + EXTRA.get(name, ()):
            try:
                v = float(r.get(col, ""))
            except ValueError:
                continue
            out.setdefault((label + (f" ({suffix})" if suffix else ""), kind), []).append(v)
    return out


def main():
    d, png = sys.argv[1], sys.argv[2]
    data = {}
    for p in sorted(glob.glob(os.path.join(d, "bench_*.csv"))):
        data.update(groups(p))
    if not data:
        print("summary_plot.py: no rows with a limit", file=sys.stderr)
        return 1
    keys = sorted(data)
    med = [statistics.median(data[k]) for k in keys]
    lo = [m - min(data[k]) for k, m in zip(keys, med)]
    hi = [max(data[k]) - m for k, m in zip(keys, med)]
    col = ["tab:blue" if k[1] == "bytes" else "tab:orange" for k in keys]
    fig, ax = plt.subplots(figsize=(8, 0.28 * len(keys) + 1.2))
    y = range(len(keys))
    ax.barh(y, med, xerr=[lo, hi], color=col, capsize=2)
    ax.set_yticks(list(y))
    ax.set_yticklabels([k[0] for k in keys], fontsize=7)
    ax.set_xscale("log")
    ax.axvline(1.0, color="k", lw=0.8)
    ax.axvline(0.5, color="gray", lw=0.6, ls="--")
    ax.set_xlabel("limit_s / seconds (blue: bytes at the measured bandwidth; orange: flops at dgemm's)",
                  fontsize=8)
    ax.invert_yaxis()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
