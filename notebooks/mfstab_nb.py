"""Helpers of the notebooks in this folder (standard library and IPython only).

Paths, from the environment (tests/run_notebooks.py sets them) or relative to notebooks/:
  MFSTAB_ROOT  the source tree (default: the parent of the current directory)
  MFSTAB_DATA  the committed data, notebooks-data/ (default ROOT/notebooks-data)
  MFSTAB       the built binary (default ROOT/build/tools/mfstab)
Nothing here writes into the source tree: fresh runs go to a temporary directory that is removed.
"""
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.environ.get("MFSTAB_ROOT") or os.path.join(os.getcwd(), ".."))
DATA = os.path.abspath(os.environ.get("MFSTAB_DATA") or os.path.join(ROOT, "notebooks-data"))
MFSTAB = os.path.abspath(os.environ.get("MFSTAB") or os.path.join(ROOT, "build", "tools", "mfstab"))
sys.dont_write_bytecode = True
if os.path.join(ROOT, "analysis") not in sys.path:
    sys.path.insert(0, os.path.join(ROOT, "analysis"))
import findings as F  # noqa: E402


def _ipython():
    from IPython.display import Image, Markdown, display
    return Image, Markdown, display


def md(text):
    """Show Markdown (plain print outside IPython)."""
    try:
        _, Markdown, display = _ipython()
        display(Markdown(text))
    except ImportError:
        print(text)


def png(name):
    """Show DATA/NAME, a figure that analysis/figures.sh made from the CSV next to it."""
    path = os.path.join(DATA, name)
    if not os.path.exists(path):
        md(f"*{name} is missing: run `bash analysis/figures.sh build notebooks-data`.*")
        return
    Image, _, display = _ipython()
    display(Image(filename=path))


def table(header, rows):
    """A Markdown table."""
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    md("\n".join(out))


def finding(f):
    """The paper's claim and mfstab's finding (analysis/findings.py), as the figure captions say them."""
    md(f"**Paper:** {F.pretty(f['paper'])}\n\n**mfstab:** {F.pretty(f['ours'])}\n\n"
       f"*Computed from* " + ", ".join(f"`{s}`" for s in f["source"]) + ".")


# ---------------------------------------------------------------- fresh run of the main job


def parse_match_table(text):
    """The table `mfstab reproduce` prints: columns separated by two or more spaces."""
    rows = []
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if not lines or not lines[0].startswith("artifact"):
        raise ValueError("mfstab reproduce printed no match table:\n" + text[:500])
    header = re.split(r"\s{2,}", lines[0].strip())
    for ln in lines[1:]:
        cells = re.split(r"\s{2,}", ln.strip())
        if len(cells) == len(header):
            rows.append(dict(zip(header, cells)))
    return header, rows


def fresh_run():
    """Run the main job's data part (analysis/figures.sh with FIGURES_PLOTS=0: `mfstab reproduce`
    and the scene runs, no plots) into a temporary directory; compare every CSV it writes with
    the committed one in DATA. Returns (match table header, rows, comparison rows, seconds): the
    table from the run's reproduce.csv (artifact, paper, mfstab, status, csv)."""
    if not os.path.exists(MFSTAB):
        raise FileNotFoundError(f"{MFSTAB}: mfstab is not built (bash scripts/build.sh)")
    build = os.path.dirname(os.path.dirname(MFSTAB))
    env = dict(os.environ, FIGURES_PLOTS="0")
    with tempfile.TemporaryDirectory(prefix="mfstab-nb-") as tmp:
        t0 = time.time()
        p = subprocess.run(["bash", os.path.join(ROOT, "analysis", "figures.sh"), build, tmp], env=env,
                           capture_output=True, text=True, timeout=120)
        secs = time.time() - t0
        if p.returncode != 0:
            raise RuntimeError(f"analysis/figures.sh exited {p.returncode}:\n{p.stderr[-2000:]}")
        parse_match_table(p.stdout)  # the printed table is there
        with open(os.path.join(tmp, "reproduce.csv"), newline="") as f:  # the same table, as CSV
            r = csv.reader(f)
            header = next(r)
            rows = [dict(zip(header, x)) for x in r]
        comparison = [compare_csv(os.path.join(tmp, n), os.path.join(DATA, n))
                      for n in sorted(os.listdir(tmp)) if n.endswith(".csv")]
    return header, rows, comparison, secs


# columns that measure rounding (a residual, a backward error): they change with the BLAS and
# LAPACK the machine uses (reference or OpenBLAS, docs/parallel.md), so they are compared with
# an absolute tolerance, as tests/golden/data/tolerances.txt does
ROUNDOFF_COLUMNS = {"arpack_residual": 1e-12, "backward_error": 1e-12}


def compare_csv(new, old, rel=1e-7):
    """(file, rows, largest deviation relative to the column's scale, status) of a fresh CSV
    against the committed one (the rounding columns of ROUNDOFF_COLUMNS: absolute)."""
    name = os.path.basename(new)
    if not os.path.exists(old):
        return (name, "", "", "not in notebooks-data")
    a = list(csv.reader(open(new, newline="")))
    b = list(csv.reader(open(old, newline="")))
    if a[0] != b[0]:
        return (name, len(a) - 1, "", "columns differ")
    if len(a) != len(b):
        return (name, f"{len(a) - 1} / {len(b) - 1}", "", "row count differs")
    worst = 0.0
    for j in range(len(a[0])):
        col_a, col_b = [r[j] for r in a[1:]], [r[j] for r in b[1:]]
        try:
            xa = [float(x) if x else math.nan for x in col_a]
            xb = [float(x) if x else math.nan for x in col_b]
        except ValueError:
            if col_a != col_b:
                return (name, len(a) - 1, "", f"column {a[0][j]} differs")
            continue
        scale = max([abs(x) for x in xa + xb if not math.isnan(x)] + [1e-300])
        atol = ROUNDOFF_COLUMNS.get(a[0][j])
        for p, q in zip(xa, xb):
            if math.isnan(p) != math.isnan(q):
                return (name, len(a) - 1, "", f"column {a[0][j]}: empty cells differ")
            if math.isnan(p):
                continue
            if atol is not None:
                if abs(p - q) > atol:
                    return (name, len(a) - 1, "", f"column {a[0][j]}: {p:g} against {q:g}")
            else:
                worst = max(worst, abs(p - q) / scale)
    return (name, len(a) - 1, f"{worst:.1e}", "same" if worst <= rel else "differs")


def show_fresh(rows_filter=None):
    """Run the main job's data part, show its match table (rows selected by ROWS_FILTER, a function
    of the artifact name) and whether the committed notebooks-data agrees; raise if it does not."""
    header, rows, comparison, secs = fresh_run()
    sel = [r for r in rows if rows_filter is None or rows_filter(r["artifact"])]
    md(f"`analysis/figures.sh` (data only: `mfstab reproduce` and the scene runs) ran in {secs:.1f} s into a "
       f"temporary directory; {len(sel)} of its {len(rows)} match-table rows belong here.")
    if sel:
        table(header, [[r[h] for h in header] for r in sel])
    stale = [c for c in comparison if c[3] != "same"]
    md(f"**Committed data:** {len(comparison) - len(stale)} of {len(comparison)} CSV files that the run wrote "
       "equal the committed ones in `notebooks-data/` (relative to each column's scale, 1e-7)." +
       ("" if not stale else " Stale: " + ", ".join(f"`{c[0]}` ({c[3]})" for c in stale) +
        " — run `bash analysis/figures.sh build notebooks-data`."))
    if stale:
        raise AssertionError("notebooks-data is stale: " + ", ".join(f"{c[0]}: {c[3]}" for c in stale))
    return header, sel


def run_mfstab(*args):
    """stdout of `mfstab ARGS` (which must not write files)."""
    p = subprocess.run([MFSTAB, *args], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        raise RuntimeError(f"mfstab {' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def run_scene(scene, *sets):
    """Rows of `mfstab run analysis/scenes/SCENE --set ...` written to a temporary file."""
    with tempfile.TemporaryDirectory(prefix="mfstab-nb-") as tmp:
        out = os.path.join(tmp, "run.csv")
        args = [MFSTAB, "run", os.path.join(ROOT, "analysis", "scenes", scene)]
        for s in sets:
            args += ["--set", s]
        p = subprocess.run(args + ["-o", out], capture_output=True, text=True, timeout=60)
        if p.returncode != 0:
            raise RuntimeError(f"mfstab run {scene}: exit {p.returncode}: {p.stderr.strip()}")
        return list(csv.DictReader(open(out, newline="")))
