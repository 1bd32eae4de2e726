#!/usr/bin/python3
"""The table of docs/benchmarks.md (lambda_max) from notebooks-data/bench_lambda.csv:
min / median / max over the repetitions per (nodes, tool, threads), the median ratio to
SciPy eigsh of the same size, and the medians of the per-product columns.

    bench_lambda_table.py notebooks-data/bench_lambda.csv
"""
import csv, statistics as st, sys
rows = list(csv.DictReader(open(sys.argv[1])))
g = {}
for r in rows:
    g.setdefault((r["nodes"], r["tool"], r["threads"]), []).append(r)
def q(v):
    v = sorted(v); return f"{v[0]:.4g} / {st.median(v):.4g} / {v[-1]:.4g}"
sci = {}
for (n, t, th), rs in g.items():
    if t == "scipy":
        sci[n] = st.median(float(r["seconds"]) for r in rs)
print("| nodes | tool | threads | seconds min / median / max | ratio to SciPy (median) | matvecs | s per matvec (median) | op s per matvec (median) | fraction (median) | op_fraction (median) | error | load_1min |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for (n, t, th), rs in sorted(g.items(), key=lambda k: (int(k[0][0]), k[0][1], k[0][2])):
    s = [float(r["seconds"]) for r in rs]
    med = lambda c: (f"{st.median(float(r[c]) for r in rs):.4g}" if all(r[c] for r in rs) else "")
    ld = [float(r["load_1min"]) for r in rs]
    print(f"| {n} | {t} | {th} | {q(s)} | {st.median(s)/sci[n]:.2f} | {rs[0]['matvecs']} | {med('s_per_matvec')} | {med('op_s_per_matvec')} | {med('fraction')} | {med('op_fraction')} | {rs[0]['error']} | {min(ld):.1f}-{max(ld):.1f} |")
