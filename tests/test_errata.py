#!/usr/bin/python3
"""The numbers docs/errata.md quotes, checked against the CSV files they come from (suite docs).

A quoted number carries a marker right after it, an HTML comment that Markdown does not show:

    blow-up at 12.9<!-- =fig06_rod.csv run=eulerian-sph | t_nonfinite_s*1e6 --> us

    =FILE            a CSV file that the main job writes (`mfstab reproduce`, analysis/figures.sh,
                     or, where the entry says so, analysis/static_studies.sh or a benchmark)
    KEY=VALUE ...    the rows: every KEY column equals VALUE (numbers compared as numbers;
                     "..." quotes a value with spaces), or matches KEY~REGEX
    | [AGG] EXPR     the value: EXPR, a Python expression of the row's columns (a column whose
                     name is not an identifier: col("name")), on the single selected row, or
                     AGG (min, max, sum, count, mean) of it over the selected rows

The quoted number must equal the value rounded to the digits it shows (3 significant digits
quote 12.9 for 12.93). An edited number, a renamed column or a changed result fails with one
line naming the entry, the number and the value.

The files `mfstab reproduce` writes are taken from a fresh run into a temporary directory AND
from the committed notebooks-data/: a quote must agree with both (so stale data fail as well as
stale text); the others (the maps and scene runs of analysis/figures.sh, the paper-level studies
of analysis/static_studies.sh, the benchmarks) from notebooks-data/.  Also checked: every
status "errata En" of the reproduce table names an entry "## En." of docs/errata.md.

usage: test_errata.py ROOT MFSTAB [ERRATA.md]"""
import csv
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile

MARK = re.compile(r"(?P<num>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)<!--\s*=(?P<spec>.*?)-->", re.S)
AGG = {"min": min, "max": max, "sum": sum, "count": len, "mean": lambda v: sum(v) / len(v)}


def as_num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return None


class Tables:
    def __init__(self, dirs):
        self.dirs, self.cache = dirs, {}

    def rows(self, d, name):
        key = (d, name)
        if key not in self.cache:
            path = os.path.join(d, name)
            self.cache[key] = list(csv.DictReader(open(path, newline=""))) if os.path.exists(path) else None
        return self.cache[key]


def evaluate(rows, sel, expr):
    """The value of a marker on the rows of one file."""
    pick = []
    for r in rows:
        ok = True
        for k, op, v in sel:
            if k not in r:
                raise ValueError(f"no column {k}")
            a, b = as_num(r[k]), as_num(v)
            if op == "~":
                ok &= re.search(v, r[k]) is not None
            else:
                ok &= (a == b) if a is not None and b is not None else r[k] == v
        if ok:
            pick.append(r)
    if not pick:
        raise ValueError("no row selected")
    agg = None
    head = expr.split(None, 1)
    if head and head[0] in AGG and len(head) > 1:
        agg, expr = head[0], head[1]

    def val(r):
        env = {"col": lambda n: num(r, n), "math": math, "abs": abs, "min": min, "max": max}
        for k in r:  # text columns stay text (an expression that uses one as a number fails)
            if k.isidentifier():
                x = as_num(r[k])
                env[k] = x if x is not None else r[k]
        return eval(expr, {"__builtins__": {}}, env)  # noqa: S307 (our own docs)

    if agg:
        return AGG[agg]([val(r) for r in pick]) if agg != "count" else len(pick)
    if len(pick) != 1:
        raise ValueError(f"{len(pick)} rows selected; name the row or an aggregate")
    return val(pick[0])


def num(r, k):
    if k not in r:
        raise ValueError(f"no column {k}")
    x = as_num(r[k])
    if x is None:
        raise ValueError(f"column {k} is not a number: {r[k]!r}")
    return x


def agrees(quoted, value):
    """quoted (text) equals value rounded to the digits the text shows."""
    q = float(quoted)
    if re.fullmatch(r"[-+]?0", quoted):  # a quoted 0 is an exact zero, to rounding
        return abs(value) <= 1e-12
    mant = re.split(r"[eE]", quoted)[0].lstrip("+-")
    exp = int(re.split(r"[eE]", quoted)[1]) if re.search(r"[eE]", quoted) else 0
    dec = len(mant.split(".")[1]) if "." in mant else 0
    half = 0.5 * 10.0 ** (exp - dec)
    return abs(value - q) <= half * (1 + 1e-9) + 1e-300


def entry_of(text, pos):
    heads = [m for m in re.finditer(r"^## (.*)$", text[:pos], re.M)]
    return heads[-1].group(1)[:50] if heads else "(top)"


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    root, mfstab = argv[1], argv[2]
    errata = argv[3] if len(argv) > 3 else os.path.join(root, "docs", "errata.md")
    text = open(errata, encoding="utf-8").read()
    committed = os.path.join(root, "notebooks-data")
    fails, passed = [], 0
    with tempfile.TemporaryDirectory(prefix="mfstab-errata-") as fresh:
        p = subprocess.run([mfstab, "reproduce", "--out", fresh], capture_output=True, text=True)
        if p.returncode != 0:
            print(f"FAIL mfstab reproduce exited {p.returncode}: {p.stderr.strip()[:300]}")
            print("test_errata: 0 passed, 1 failed")
            return 1
        tables = Tables([fresh, committed])
        marks = list(MARK.finditer(text))
        for m in marks:
            where = f"{entry_of(text, m.start())}: {m.group('num')}"
            try:
                parts = m.group("spec").split("|", 1)
                if len(parts) != 2:
                    raise ValueError("expected =FILE [KEY=VALUE ...] | EXPR")
                words = shlex.split(parts[0])
                name, sel = words[0], []
                for w in words[1:]:
                    m2 = re.match(r"([^=~]+)([=~])(.*)$", w, re.S)
                    if not m2:
                        raise ValueError(f"a selector is not KEY=VALUE or KEY~REGEX: {w!r}")
                    sel.append(m2.groups())
                dirs = [d for d in (fresh, committed) if tables.rows(d, name) is not None]
                if not dirs:
                    raise ValueError(f"{name}: neither mfstab reproduce nor notebooks-data has it")
                if fresh not in dirs:
                    dirs = [committed]
                for d in dirs:
                    v = evaluate(tables.rows(d, name), sel, parts[1].strip())
                    src = "a fresh mfstab reproduce" if d == fresh else "notebooks-data"
                    if not agrees(m.group("num"), v):
                        raise ValueError(f"{name} in {src} gives {v:.6g}")
                passed += 1
            except (ValueError, SyntaxError, NameError, KeyError, ZeroDivisionError, TypeError) as e:
                fails.append(f"FAIL {where}: {e}")
        # every errata status of the table names an entry that exists
        heads = set(re.findall(r"^## (E\d+)\.", text, re.M))
        for r in csv.DictReader(open(os.path.join(fresh, "reproduce.csv"), newline="")):
            st = r["status"]
            if st.startswith("errata"):
                e = st.split()[-1]
                if e not in heads:
                    fails.append(f"FAIL reproduce row {r['artifact']!r}: status {st}, but docs/errata.md has no ## {e}.")
                else:
                    passed += 1
    for f in fails:
        print(f)
    print(f"{len(marks)} quoted numbers checked")
    print(f"test_errata: {passed} passed, {len(fails)} failed")
    return 1 if fails or not marks else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
