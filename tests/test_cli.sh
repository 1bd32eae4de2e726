#!/usr/bin/env bash
# Tests of the mfstab command-line program: exit codes, one-line errors that
# name the parameter, no output file after a failure, and the numbers of two
# good runs (paper 003 Table I, and the linear finite element in 1D).
# usage: bash tests/test_cli.sh /path/to/mfstab
# One line per failed check; the last line counts them; exit 1 on any failure.
set -u
M=${1:?usage: bash tests/test_cli.sh /path/to/mfstab [scenes-dir]}
SCENES=${2:-$(dirname "$0")/../analysis/scenes}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0

ok() { pass=$((pass + 1)); }
ko() {
  fail=$((fail + 1))
  echo "FAIL: $*"
}
# check DESCRIPTION COMMAND...: passes when COMMAND succeeds.
check() {
  local what=$1
  shift
  if "$@"; then ok; else ko "$what"; fi
}

# run ARGS...: runs mfstab; sets rc, and out/err to files holding stdout/stderr.
out=$tmp/stdout
err=$tmp/stderr
run() {
  "$M" "$@" >"$out" 2>"$err"
  rc=$?
}
nlines() { wc -l <"$1" | tr -d ' '; }
no_tmp_left() { ! compgen -G "$tmp/res/*.tmp*" >/dev/null; }

# --- help and commands -------------------------------------------------------
run --help
check "mfstab --help: exit $rc, want 0" test "$rc" -eq 0
check "mfstab --help: no usage on stdout" grep -q '^usage: mfstab' "$out"
run stencil --help
check "mfstab stencil --help: exit $rc, want 0" test "$rc" -eq 0
check "mfstab stencil --help: no usage on stdout" grep -q '^usage: mfstab stencil' "$out"
check "mfstab stencil --help: options not listed" grep -q -- '--dilation' "$out"
run frobnicate
check "mfstab frobnicate: exit $rc, want 2" test "$rc" -eq 2
check "mfstab frobnicate: $(nlines "$err") lines on stderr, want 1" test "$(nlines "$err")" -eq 1
check "mfstab frobnicate: message does not name the command" grep -q "frobnicate" "$err"
run
check "mfstab (no command): exit $rc, want 2" test "$rc" -eq 2

# --- bad input ---------------------------------------------------------------
# bad_input PARAM ARGS...: mfstab stencil -o FILE ARGS must exit 2 with one
# line on stderr naming PARAM, print nothing on stdout, and leave no file.
bad_input() {
  bad_cmd stencil "$@"
}
# bad_cmd COMMAND PARAM ARGS...: the same for any command.
bad_cmd() {
  local cmd=$1 param=$2
  shift 2
  mkdir -p "$tmp/res"
  local res=$tmp/res/out.csv
  run "$cmd" -o "$res" "$@"
  local what="mfstab $cmd $*"
  check "$what: exit $rc, want 2" test "$rc" -eq 2
  check "$what: $(nlines "$err") lines on stderr, want 1" test "$(nlines "$err")" -eq 1
  check "$what: stderr does not name $param: $(head -c 200 "$err")" grep -q -F -- "$param" "$err"
  check "$what: output on stdout" test ! -s "$out"
  check "$what: output file left behind" test ! -e "$res"
  check "$what: temporary file left behind" no_tmp_left
  rm -rf "$tmp/res"
}
bad_input --frobnicate --frobnicate 1
bad_input --dilation --dilation 2.x
bad_input --dilation --dilation 0
bad_input --dilation --dilation -1
bad_input --dilation --dim 2 --dilation 0.9 --shape mls
bad_input --kernel --kernel gaussian
bad_input --quadrature --quadrature gauss0
bad_input --quadrature --quadrature simpson
bad_input --quadrature --dim 1 --quadrature stress-quad
bad_input --quadrature --dim 2 --lattice square --quadrature stress-hex
bad_input --dilation --dilation
bad_input --dim --dim 3

# dispersion (von Neumann analysis)
bad_cmd dispersion --theta --dim 1 --theta 0,45
bad_cmd dispersion --stress --stress ''
bad_cmd dispersion --stress --stress 0.1,,0.2
bad_cmd dispersion --stress --stress 0.1,x
bad_cmd dispersion --dilation --dilation 1.5,0
bad_cmd dispersion --dilation --dim 2 --dilation 0.9
bad_cmd dispersion --ls-length --ls-length 1
bad_cmd dispersion --frame --frame spatial
bad_cmd dispersion --points --points 1
bad_cmd dispersion --kappa --kappa 0.5 --points 10
bad_cmd dispersion --stretch --dim 2 --stretch 1.1

# eigs and bound (finite models)
bad_cmd eigs --nodes --nodes 4 --periodic --dilation 2
bad_cmd eigs --nodes --nodes 3 --dilation 3
bad_cmd eigs --periodic --periodic --fixed ends
bad_cmd eigs --periodic --dim 2 --periodic --fixed boundary
bad_cmd eigs --modulus --modulus 0
bad_cmd eigs --modulus --modulus -1
bad_cmd eigs --density --density 0
bad_cmd eigs --nodes --nodes 10,x
bad_cmd eigs --nodes --nodes 10,10
bad_cmd eigs --nodes --dim 2 --nodes 10,10,10
bad_cmd eigs --nodes --nodes 1
bad_cmd eigs --fixed --dim 2 --fixed ends
bad_cmd eigs --tol --tol 0
bad_cmd bound --nodes --nodes 4 --periodic --dilation 2
bad_cmd bound --zero-modes --zero-modes

# a numerical failure (ARPACK stopped after one iteration): exit 1, no file
mkdir -p "$tmp/res"
run eigs --nodes 3000 --maxiter 1 --ncv 3 --arpack-tol 1e-15 -o "$tmp/res/out.csv"
check "eigs with --maxiter 1: exit $rc, want 1" test "$rc" -eq 1
check "eigs with --maxiter 1: $(nlines "$err") lines on stderr, want 1" test "$(nlines "$err")" -eq 1
check "eigs with --maxiter 1: output file left behind" test ! -e "$tmp/res/out.csv"
check "eigs with --maxiter 1: temporary file left behind" no_tmp_left
rm -rf "$tmp/res"

# the linear finite element: 1D, D = 1, gauss2, 41 nodes on [0, 1]: lambda_max dx^2 = 4
run eigs --nodes 41 --length 1 --quadrature gauss2 --dilation 1
check "eigs linear FE: exit $rc: $(head -c 200 "$err")" test "$rc" -eq 0
lm=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i } NR == 2 { printf "%.10f", $h["lambda_max"] / 1600 }' "$out")
check "eigs linear FE: lambda_max dx^2 = '$lm', want 4" awk -v v="$lm" 'BEGIN { d = v - 4; exit !(v != "" && d < 1e-9 && d > -1e-9) }'

# --- mfstab static (paper 004): bad input, numerical failures, good runs -------
bad_cmd static --method --method fem
bad_cmd static --method --method sph,fem
bad_cmd static --method --method efg,efg
bad_cmd static --problem --problem disc
bad_cmd static --nodes --nodes 1,3
bad_cmd static --nodes --nodes 17
bad_cmd static --nodes --nodes 17,x
bad_cmd static --nodes --problem plate-hole --nodes 2
bad_cmd static --nodes --problem plate-hole --nodes 6,7
bad_cmd static --dilation --method mls --dilation 0.9
bad_cmd static --dilation --method efg --dilation 0.9
bad_cmd static --dilation --method jb --dilation 0.9
bad_cmd static --dilation --method cd2 --nodes 3,2 --dilation 0.7
bad_cmd static --dilation --dilation 0
bad_cmd static --poisson --poisson 0.5
bad_cmd static --young --young 0
bad_cmd static --load --load 0
bad_cmd static --refine --refine 0
bad_cmd static --refine --refine 12
bad_cmd static --patch --patch --refine 2
bad_cmd static --perturb --problem plate-hole --perturb 0.1
bad_cmd static --perturb --perturb 0.5
bad_cmd static --hole-radius --hole-radius 0.5
bad_cmd static --plate-size --problem plate-hole --plate-size 2
bad_cmd static --quadrature --quadrature stress-quad
bad_cmd static --solver --solver lapack
bad_cmd static --solver --method cd1 --solver cholmod
bad_cmd static --solve-rcond-min --solve-rcond-min 1
bad_cmd static --ebc --ebc layer
bad_cmd static --ebc --problem plate-hole --ebc ghost
# a singular system (sph with a < dx: every gradient vanishes, K = 0), and a
# condition threshold above the solver's estimate: exit 1, one line, no file
for args in "--method sph --dilation 0.9" "--method rl --solve-rcond-min 0.9" \
            "--method sph --dilation 0.9 --solver umfpack"; do
  mkdir -p "$tmp/res"
  run static $args -o "$tmp/res/out.csv"
  check "static $args: exit $rc, want 1" test "$rc" -eq 1
  check "static $args: $(nlines "$err") lines on stderr, want 1" test "$(nlines "$err")" -eq 1
  check "static $args: message does not say singular: $(cat "$err")" grep -q "singular" "$err"
  check "static $args: output file left behind" test ! -e "$tmp/res/out.csv"
  check "static $args: temporary file left behind" no_tmp_left
  rm -rf "$tmp/res"
done
run static --help
check "static --help: exit $rc" test "$rc" -eq 0
for o in --problem --method --nodes --refine --patch --kernel --dilation --quadrature --young --ebc \
         --poisson --plane-strain --load --length --depth --hole-radius --plate-size --perturb \
         --seed --solver --solve-rcond-min; do
  check "static --help does not list $o" grep -q -- "$o" "$out"
done
# the nodal solution: the columns, u^h at the nodes, the exact solution beside it
run static --method efg --nodes 33,5
check "static nodal: exit $rc: $(head -c 200 "$err")" test "$rc" -eq 0
check "static nodal: header '$(head -n 1 "$out")'" test "$(head -n 1 "$out")" = "method,x_m,y_m,ux_m,uy_m,ux_exact_m,uy_exact_m"
check "static nodal: $(nlines "$out") lines, want 166 (33 x 5 nodes)" test "$(nlines "$out")" -eq 166
tip=$(awk -F, '$2 == 8 && $3 == 0 { printf "%.6f %.6f", $5, $7 }' "$out")
check "static nodal: EFG tip deflection and exact '$tip', want 2.0700 (P L (8 L^2 + (4 + 5 nu) D^2) / (2 E D^3)) within 1e-4" \
  awk -v t="$tip" 'BEGIN { split(t, v, " "); d = v[1] - v[2]; exit !(v[2] == 2.070000 && d < 1e-4 && d > -1e-4) }'
run static --method mls --nodes 33,5 --ebc ghost
check "static --ebc ghost: exit $rc: $(head -c 200 "$err")" test "$rc" -eq 0
check "static --ebc ghost: $(nlines "$out") lines, want 166 (the ghost columns not written)" test "$(nlines "$out")" -eq 166
check "static --ebc ghost: a node at x < 0 written" awk -F, 'NR > 1 && $2 < 0 { exit 1 }' "$out"
# a study: one row per method and level, the fitted rates
run static --method efg,sph --refine 3
check "static study: exit $rc: $(head -c 200 "$err")" test "$rc" -eq 0
check "static study: $(nlines "$out") lines, want 7" test "$(nlines "$out")" -eq 7
rates=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
  $h["level"] == 3 { printf "%s %s %s ", $h["method"], $h["rate_L2"], $h["rate_energy"] }' "$out")
check "static study: EFG L2 rate >= 1.8 and energy >= 0.9, SPH energy < 0.3: '$rates'" \
  awk -v r="$rates" 'BEGIN { split(r, v, " "); exit !(v[1] == "efg" && v[2] >= 1.8 && v[3] >= 0.9 && v[4] == "sph" && v[6] < 0.3) }'
check "static study: NaN or inf" bash -c "! grep -qiE 'nan|inf' '$out'"
run static --method all --patch --nodes 33,5
check "static --patch: exit $rc: $(head -c 200 "$err")" test "$rc" -eq 0
repro=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next } { printf "%s:%s ", $h["method"], $h["reproduces_1e-10"] }' "$out")
check "static --patch: reproduction flags '$repro'" test "$repro" = "sph:0 jb:0 rl:1 cd1:1 cd2:1 mls:1 efg:1 "

# --- a good run: Table I, 2x2 cell quadrature --------------------------------
mkdir -p "$tmp/res"
csv=$tmp/res/table1.csv
args=(stencil --dim 2 --kernel cubic --dilation 2 --shape mls --quadrature gauss2)
run "${args[@]}" -o "$csv"
check "mfstab ${args[*]} -o FILE: exit $rc, want 0: $(head -c 200 "$err")" test "$rc" -eq 0
check "mfstab ${args[*]} -o FILE: stderr not empty" test ! -s "$err"
check "mfstab ${args[*]} -o FILE: output on stdout" test ! -s "$out"
check "mfstab ${args[*]} -o FILE: no output file" test -s "$csv"
check "mfstab ${args[*]} -o FILE: temporary file left behind" no_tmp_left
if [ -s "$csv" ]; then
  check "header is '$(head -n 1 "$csv")', want 'j,k,K,M'" test "$(head -n 1 "$csv")" = "j,k,K,M"
  check "NaN or inf in the output" bash -c "! grep -qiE 'nan|inf' '$csv'"
  k00=$(awk -F, '$1 == 0 && $2 == 0 { printf "%.4f", $3 }' "$csv")
  check "K(0,0) = '$k00', want 0.6507 (Table I, cell integration 2x2)" test "$k00" = "0.6507"
  check "every row has 4 fields" awk -F, 'NF != 4 { exit 1 }' "$csv"
  run "${args[@]}"
  check "standard output differs from the -o file" cmp -s "$out" "$csv"
fi
rm -rf "$tmp/res"

# --- 1D, D = 1: EFG reproduces the hat functions, K = [-1 2 -1] --------------
args=(stencil --dim 1 --dilation 1 --quadrature gauss2 --shape mls)
run "${args[@]}"
check "mfstab ${args[*]}: exit $rc, want 0: $(head -c 200 "$err")" test "$rc" -eq 0
msg=$(awk -F, '
  NR == 1 { next }
  { want = ($1 == 0) ? 2 : (($1 == 1 || $1 == -1) ? -1 : 0); seen[$1] = 1
    d = $3 - want; if (d < 0) d = -d
    if (d > 1e-12) printf "K(%s,%s) = %s, want %d; ", $1, $2, $3, want }
  END { for (j = -1; j <= 1; j++) if (!((j "") in seen)) printf "K(%d,0) missing; ", j }' "$out")
check "1D linear finite element: $msg" test -z "$msg"
m00=$(awk -F, '$1 == 0 && $2 == 0 { print $4 }' "$out")
check "1D lumped mass M(0,0) = '$m00', want 1 (density * dx)" awk -v m="$m00" 'BEGIN { d = m - 1; exit !(m != "" && d < 1e-12 && d > -1e-12) }'

# --- output files: never replace a special file, honour the umask, no temporary left
o=$tmp/outs
mkdir -p "$o"
no_tmp_in() { ! compgen -G "$1/*.tmp*" >/dev/null; }
run stencil
want=$(cat "$out")
mkfifo "$o/fifo"
(timeout 20 cat "$o/fifo" >"$o/from_fifo") &
reader=$!
run stencil -o "$o/fifo"
wait "$reader"
check "-o FIFO: exit $rc, want 0: $(head -c 200 "$err")" test "$rc" -eq 0
check "-o FIFO: the FIFO was replaced" test -p "$o/fifo"
check "-o FIFO: the reader did not get the CSV" test "$(cat "$o/from_fifo")" = "$want"
if [ "$(id -u)" -eq 0 ]; then
  mknod "$o/null" c 1 3
  run stencil -o "$o/null"
  check "-o device: exit $rc, want 0" test "$rc" -eq 0
  check "-o device: the device node was replaced" test -c "$o/null"
fi
run stencil -o /dev/null
check "-o /dev/null: exit $rc, want 0" test "$rc" -eq 0
check "-o /dev/null: no longer a character device" test -c /dev/null
echo old >"$o/target.csv"
chmod 640 "$o/target.csv"
ln -s target.csv "$o/link.csv"
run stencil -o "$o/link.csv"
check "-o symlink: exit $rc, want 0" test "$rc" -eq 0
check "-o symlink: the link was replaced by a file" test -L "$o/link.csv"
check "-o symlink: the target does not hold the CSV" test "$(cat "$o/target.csv")" = "$want"
check "-o symlink: the target lost its mode 640" test "$(stat -c %a "$o/target.csv")" = 640
ln -s new.csv "$o/dangling.csv"
run stencil -o "$o/dangling.csv"
check "-o dangling symlink: exit $rc, want 0" test "$rc" -eq 0
check "-o dangling symlink: the target was not created" test "$(cat "$o/new.csv" 2>/dev/null)" = "$want"
for m in 022 027 002; do
  (umask $m && "$M" stencil -o "$o/u$m.csv")
  mode=$(stat -c %a "$o/u$m.csv")
  check "-o with umask $m: mode $mode, want $(printf '%o' $((0666 & ~0$m)))" test "$mode" = "$(printf '%o' $((0666 & ~0$m)))"
done
run stencil -o "$o/missing/x.csv"
check "-o in a missing directory: exit $rc, want 2" test "$rc" -eq 2
check "-o in a missing directory: $(nlines "$err") lines on stderr, want 1" test "$(nlines "$err")" -eq 1
run stencil -o "$o"
check "-o DIRECTORY: exit $rc, want 2" test "$rc" -eq 2
check "-o DIRECTORY: message does not say it is a directory" grep -q "is a directory" "$err"
mkdir "$o/ro"
chmod 555 "$o/ro"
run stencil -o "$o/ro/x.csv"
if [ "$(id -u)" -eq 0 ]; then
  check "-o in a read-only directory as root: exit $rc, want 0" test "$rc" -eq 0
else
  check "-o in a read-only directory: exit $rc, want 2" test "$rc" -eq 2
  check "-o in a read-only directory: a file was created" test ! -e "$o/ro/x.csv"
fi
check "-o in a read-only directory: temporary file left behind" no_tmp_in "$o/ro"
chmod 755 "$o/ro"
# a signal halfway: the long run is killed once its temporary file exists
for sig in INT TERM HUP PIPE; do
  "$M" run "$SCENES/rod-growth.ini" --set model.nodes=20000 --set model.length=20 \
    --set time.end=1 --set discretization.frame=lagrangian --set output.every=100 \
    -o "$o/sig.csv" >/dev/null 2>&1 &
  pid=$!
  for _ in $(seq 200); do compgen -G "$o/sig.csv.tmp*" >/dev/null && break; sleep 0.05; done
  seen=$(compgen -G "$o/sig.csv.tmp*" >/dev/null && echo 1 || echo 0)
  kill -"$sig" "$pid"
  wait "$pid"
  src=$?
  check "SIG$sig halfway: the temporary file never appeared" test "$seen" -eq 1
  check "SIG$sig halfway: exit $src, want death by the signal" test "$src" -gt 128
  check "SIG$sig halfway: temporary file left behind" no_tmp_in "$o"
  check "SIG$sig halfway: an output file was written" test ! -e "$o/sig.csv"
done
rm -rf "$o"

# --- the main job: mfstab reproduce -------------------------------------------
mkdir -p "$tmp/repro"
run reproduce --out "$tmp/repro"
check "mfstab reproduce: exit $rc, want 0: $(head -c 300 "$err")" test "$rc" -eq 0
bad_status=$(awk 'NR > 1 && $NF != "match" && $NF != "errata" && $NF != "data"' "$out")
check "mfstab reproduce: rows neither match, errata nor data: $bad_status" test -z "$bad_status"
t1=$(grep -c '^Table I .* match$' "$out" || true)
check "mfstab reproduce: $t1 Table I columns match, want 4 (every printed entry, from mfstab stencil)" test "$t1" -eq 4
check "mfstab reproduce: Table II Eulerian stress points listed as errata (docs/errata.md E1)" grep -q 'Table II stress points, Eulerian kernel .*errata$' "$out"
for f in table1_nodal table1_gauss2 table1_gauss1 table1_stress-quad table2 fig03 fig04 fig09 fig10 \
         fig11_alpha0.01 fig13 fig14a fig14b fig15a fig15b fig15c fig15d fig17_cubic fig18_cubic; do
  check "mfstab reproduce: $f.csv missing or empty" test -s "$tmp/repro/$f.csv"
done
check "mfstab reproduce: NaN or inf in a CSV" bash -c "! grep -qiE 'nan|inf' $tmp/repro/*.csv"
rm -rf "$tmp/repro"

echo "test_cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
