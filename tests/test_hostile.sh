#!/usr/bin/env bash
# The hostile inputs of issue 12, re-run: each must end in exit 2 (bad input)
# or 1 (numerical failure) with one line on stderr naming the parameter and no
# output file, or in exit 0 with every number in the CSV finite.  No signal,
# no hang (each run is limited to 60 s).
# usage: bash tests/test_hostile.sh /path/to/mfstab scenes-dir
set -u
M=${1:?usage: bash tests/test_hostile.sh /path/to/mfstab scenes-dir}
S=${2:?usage: bash tests/test_hostile.sh /path/to/mfstab scenes-dir}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }

# hostile WANT PARAM ARGS...: WANT is 2, 1, 0 or "0|1" (finite output or a
# numerical failure); PARAM must appear in the message of a refusal.
hostile() {
  local want=$1 param=$2
  shift 2
  local o=$tmp/out.csv what="mfstab $*"
  rm -f "$o"
  (if [ -n "${LIMIT_KB:-}" ]; then ulimit -v "$LIMIT_KB"; fi
   exec timeout 60 "$M" "$@" -o "$o") >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$? n
  n=$(wc -l <"$tmp/stderr" | tr -d ' ')
  case "|$want|" in
  *"|$rc|"*) ;;
  *) ko "$what: exit $rc, want $want: $(head -c 200 "$tmp/stderr")"; return ;;
  esac
  if [ "$rc" -eq 0 ]; then
    # no field nan or inf (undefined values are empty cells)
    if awk -F, 'NR > 1 { for (i = 1; i <= NF; i++) if (tolower($i) ~ /^[-+]?(nan|inf)/) { bad = 1; exit } } END { exit !bad }' "$o"; then
      ko "$what: a field that is not a finite number"
      return
    fi
  else
    [ "$n" -eq 1 ] || { ko "$what: $n lines on stderr, want 1"; return; }
    grep -q -F -- "$param" "$tmp/stderr" || { ko "$what: message does not name $param: $(head -c 200 "$tmp/stderr")"; return; }
    [ ! -e "$o" ] || { ko "$what: an output file after a failure"; return; }
    [ ! -s "$tmp/stdout" ] || { ko "$what: output on stdout"; return; }
  fi
  pass=$((pass + 1))
}

# NaN or inf with exit 0
hostile 2 pulse_center run "$S/gaussian-pulse.ini" --set initial.pulse_center=1
hostile "0|1" pulse_amplitude run "$S/plate-pulse-2d.ini" --set initial.pulse_amplitude=1e30
hostile "0|1" center_velocity run "$S/tsph-elastic-bar.ini" --set initial.center_velocity=1e30
hostile "0|1" center_velocity run "$S/tsph-viscoplastic-bar.ini" --set initial.center_velocity=1e30
hostile 2 --kappa dispersion --kappa 1e308
hostile 2 --theta dispersion --dim 2 --theta 1e308
hostile 2 --stretch dispersion --stretch 1e308
hostile 2 --stress dispersion --stress 1e308
# crashes
hostile 2 every run "$S/gaussian-pulse.ini" --set output.every=4294967296
hostile 2 length_y run "$S/plate-pulse-2d.ini" --set model.length_y=1e308
hostile 2 --dilation eigs --dilation 3e9
hostile 2 --dilation eigs --dilation 1e6
# the library printing
hostile 2 --modulus eigs --modulus 1e308
hostile 2 --spacing eigs --dim 2 --spacing 1e308
# work without bound
sed -e 's/^safety = .*/dt = 1e-30/' "$S/gaussian-pulse.ini" >"$tmp/tiny-dt.ini"
hostile 2 max_steps run "$tmp/tiny-dt.ini"
hostile 2 end run "$S/gaussian-pulse.ini" --set time.end=1e30
hostile 2 max_entries run "$S/plate-pulse-2d.ini" --set model.nodes=200 --set model.nodes_y=200 --set model.length_y=0.031 --set discretization.dilation=40
hostile 2 --max-entries eigs --nodes 200000 --dilation 5000
# static and map without a limit ran for hours: refused, naming the size and the override
hostile 2 --nodes static --nodes 100000,3000
hostile 2 --max-entries static --nodes 100000,3000
hostile 2 --max-entries static --problem plate-hole --nodes 3000 --method sph
hostile 2 --max-entries static --nodes 17,3 --refine 6 --max-entries 1e6
hostile 2 --stretch-range map --stretch-range 0.5:1.5:100000
hostile 2 --max-evaluations map --stretch-range 0.5:1.5:100000
hostile 2 --max-evaluations map --stretch-range 0.5:1.5:3 --directions 10000 --wavenumbers 100000
hostile 2 --max-evaluations map --stress-range -1:1:3 --max-evaluations 100
hostile 0 --max-evaluations map --stress-range -1:1:3 --max-evaluations 1e4
# more memory than the process may take (an address-space limit, as a cgroup
# or a small machine would impose): refused up front (exit 2) or out of memory
# (exit 1), never killed
# (not under AddressSanitizer, which reserves terabytes of address space for its shadow)
if ! ldd "$M" 2>/dev/null | grep -q libasan; then
  LIMIT_KB=1500000 hostile 2 memory eigs --dim 2 --nodes 1000,1000 --dilation 3
  LIMIT_KB=1500000 hostile "1|2" memory eigs --dim 2 --nodes 700,700 --dilation 3 --physics plane-strain --max-entries 1e9
fi
# parsing
# a comment line past the line buffer that ends in a key (inih read its tail as a key)
{ cat "$S/rod-tensile.ini"; printf '; %s force = 1\n' "$(printf '%0300d' 0)"; } >"$tmp/long.ini"
hostile 2 "long.ini:" run "$tmp/long.ini"
hostile 2 --modulus eigs --modulus 0x10
hostile 2 --modulus eigs --modulus " 1"
hostile 2 --modulus eigs --modulus 1e400
hostile 0 --kappa dispersion --kappa 1e-308,0.5
hostile 2 --periodic eigs --periodic=0
hostile 2 --frobnicate eigs --nodes 20 --frobnicate
hostile 2 --nodes eigs --nodes
hostile 2 "directory" run "$S"
hostile 2 "mfstab reproduce" reproduce --out /etc/passwd
hostile 2 "perturbation" run "$S/rod-tensile.ini" --set initial.perturbation=1e30

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
