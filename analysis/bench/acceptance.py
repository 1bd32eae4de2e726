#!/usr/bin/python3
"""The benchmark targets of issues 14 and 15, read off the committed CSVs.

Every target of the two issues that a benchmark measures is one row: the
quantity, its target, and min / median / max over the runs (repetitions) of
the CSV that measures it, with the range of the 1-minute load average those
runs saw and whether the target holds in every run (met = all), in the median
run only (median) or not (no).  Nothing is measured here: this only reads
notebooks-data/bench_*.csv (written by analysis/bench/run.sh and the scripts
it calls), so the table is as old as the CSVs it names.

Writes notebooks-data/bench_acceptance.csv:
  issue,item,quantity,target,unit,runs,min,median,max,load_min,load_max,met,source
and, with --markdown FILE, the same as a Markdown table (docs/bench_acceptance.md).
A target whose CSV or rows are missing gets runs = 0 and met = "not measured".

usage: /usr/bin/python3 analysis/bench/acceptance.py [--data DIR] [-o FILE] [--markdown FILE]
"""
import argparse
import csv
import math
import os
import statistics
import sys


def rows(data, name):
    path = os.path.join(data, name)
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(s):
    try:
        v = float(s)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def where(rs, **eq):
    return [r for r in rs if all(r.get(k) == v for k, v in eq.items())]


def reps(rs, key="rep"):
    """Rows of single repetitions (not the min/median/max summaries)."""
    out = []
    for r in rs:
        v = r.get(key, "")
        if v.isdigit() or (v.startswith("rep") and v[3:].isdigit()):
            out.append(r)
    return out


def loads(rs, key):
    return [v for v in (num(r.get(key)) for r in rs) if v is not None]


# ---------------------------------------------------------------------------
# the targets: each returns (values, loads, source, note)


def t_disp_1d(d):
    rs = [r for r in rows(d, "bench_dispersion_numpy.csv")
          if r["comparison"] == "shared/ray-stresses" and r["run"].isdigit()]
    return [num(r["c_ns_per_point"]) for r in rs], loads(rs, "load1"), \
        "bench_dispersion_numpy.csv comparison=shared/ray-stresses, c_ns_per_point"


def t_disp_1d_numpy(d):
    rs = [r for r in rows(d, "bench_dispersion_numpy.csv")
          if r["family"] == "1d" and r["run"].isdigit()]
    # the weaker of the two 1D comparisons, run by run
    by = {}
    for r in rs:
        by.setdefault(r["run"], []).append(num(r["ratio"]))
    return [min(v) for v in by.values()], loads(rs, "load1"), \
        "bench_dispersion_numpy.csv family=1d, ratio (NumPy / C; the smaller of the two comparisons)"


def t_disp_2d(d):
    rs = [r for r in rows(d, "bench_dispersion_numpy.csv")
          if r["family"] == "2d-antiplane" and r["run"].isdigit()]
    return [num(r["c_ns_per_point"]) for r in rs], loads(rs, "load1"), \
        "bench_dispersion_numpy.csv family=2d-antiplane, c_ns_per_point (one branch)"


def t_disp_2d_branch(d):
    """The other 2D families' ray phase per branch (one process, its repeats)."""
    out, ld = [], []
    for r in rows(d, "bench_dispersion.csv"):
        if r["family"].startswith("2d") and r["phase"] == "ray":
            n, b = num(r["points"]), num(r["branches"])
            if n and b:
                out.append((r["family"], [1e9 * num(r[k]) / (n * b) for k in
                                          ("seconds_min", "seconds_median", "seconds_max")]))
                ld += loads([r], "load1")
    return out, ld


def t_disp_2d_numpy(d):
    rs = [r for r in rows(d, "bench_dispersion_numpy.csv")
          if r["family"] == "2d-antiplane" and r["run"].isdigit()]
    return [num(r["ratio"]) for r in rs], loads(rs, "load1"), \
        "bench_dispersion_numpy.csv family=2d-antiplane, ratio (NumPy / C)"


def lambda_rows(d, tool, threads):
    rs = where(rows(d, "bench_lambda.csv"), tool=tool, threads=threads)
    big = max((int(r["nodes"]) for r in rs), default=0)
    return [r for r in rs if int(r["nodes"]) == big], big


def t_lambda_fraction(tool, threads):
    def f(d):
        rs, n = lambda_rows(d, tool, threads)
        return [num(r["fraction"]) for r in rs], loads(rs, "load_1min"), \
            f"bench_lambda.csv tool={tool} threads={threads} nodes={n}, fraction"
    return f


def t_lambda_iter(threads):
    def f(d):
        rs, n = lambda_rows(d, "mfstab-lanczos", threads)
        return [num(r.get("iter_fraction")) for r in rs], loads(rs, "load_1min"), \
            f"bench_lambda.csv tool=mfstab-lanczos threads={threads} nodes={n}, iter_fraction"
    return f


def t_lambda_vs_scipy(tool, threads):
    def f(d):
        rs, n = lambda_rows(d, tool, threads)
        sp = {r["rep"]: num(r["seconds"]) for r in lambda_rows(d, "scipy", "1")[0]}
        v = [num(r["seconds"]) / sp[r["rep"]] for r in rs if sp.get(r["rep"])]
        return v, loads(rs, "load_1min"), \
            f"bench_lambda.csv nodes={n}: seconds of tool={tool} threads={threads} / scipy, same rep"
    return f


def t_step(d):
    rs = [r for r in rows(d, "bench_step.csv") if r["rule"] == "gershgorin"]
    return [num(r["time_ratio_power"]) for r in rs], loads(rs, "load_1min"), \
        "bench_step.csv rule=gershgorin, time_ratio_power (median times; one row per model)"


def t_assembly(col, phase="total"):
    def f(d):
        rs = [r for r in rows(d, "bench_assembly.csv") if r.get("phase") == phase and col in r]
        big = max((int(r["nodes"]) for r in rs), default=0)
        rs = [r for r in rs if int(r["nodes"]) == big and r.get("mode", "model") == "model"]
        return [num(r[col]) for r in rs], loads(rs, "load_1min"), \
            f"bench_assembly.csv mode=model phase={phase} nodes={big}, {col}"
    return f


def t_mpi_error(d):
    rs = [r for r in rows(d, "bench_mpi.csv") if r["mode"] == "mpi" and r["ranks"] == "2"]
    return [num(r["error"]) for r in rs], loads(rs, "load_1min"), \
        "bench_mpi.csv mode=mpi ranks=2, error (|lambda - serial| / lambda)"


def t_limits(d):
    names = sorted(f for f in os.listdir(d) if f.startswith("bench_") and f.endswith(".csv")
                   and f != "bench_acceptance.csv")
    missing = []
    for n in names:
        rs = rows(d, n)
        if rs and "limit_kind" in rs[0] and all(r["limit_kind"] in ("", "none") for r in rs):
            missing.append(n)
    share = [1.0 - len(missing) / len(names)] if names else []
    return share, [], "CSVs with a limit: " + (("none for " + " ".join(missing)) if missing
                                               else "all")


def t_check_read(d):
    rs = [r for r in rows(d, "bench_check.csv")
          if r["job"] == "particles" and r["phase"] == "total" and r["blas"] == "default"
          and r["stat"].startswith("rep")]
    return [num(r["cpu_seconds"]) for r in rs], loads(rs, "load_1min"), \
        "bench_check.csv job=particles phase=total (read + geometry + plan + gershgorin), cpu_seconds"


def t_certify(variant, threads):
    def f(d):
        rs = [r for r in rows(d, "bench_check.csv")
              if r["job"] == "certify" and r["variant"] == variant and r["phase"] == "time_ratio"
              and r["blas"] == "default" and r["stat"].startswith("rep")
              and r.get("threads", "1") == threads]
        big = max((int(r["particles"]) for r in rs), default=0)
        rs = [r for r in rs if int(r["particles"]) == big]
        return [num(r["seconds"]) for r in rs], loads(rs, "load_1min"), \
            f"bench_check.csv certify {variant} threads={threads} particles={big}, time_ratio (wall)"
    return f


LE, GE = "<=", ">="
TARGETS = [
    # issue, item, quantity, comparator, target, unit, function
    (14, 3, "1D dispersion after the plan, all stresses of a ray", LE, 20, "ns/point", t_disp_1d),
    (14, 3, "1D dispersion: NumPy time / mfstab time", GE, 2.5, "ratio", t_disp_1d_numpy),
    (14, 3, "2D anti-plane dispersion per branch", LE, 60, "ns/point/branch", t_disp_2d),
    (14, 3, "2D dispersion: NumPy time / mfstab time", GE, 2.5, "ratio", t_disp_2d_numpy),
    (14, 4, "lambda_max, 1 thread: fraction of the bandwidth limit per product", GE, 0.5,
     "fraction", t_lambda_fraction("mfstab", "1")),
    (14, 4, "lambda_max, 2 threads: fraction of the bandwidth limit per product", GE, 0.5,
     "fraction", t_lambda_fraction("mfstab", "2")),
    (14, 4, "lambda_max (Lanczos), 1 thread: fraction of the limit per product", GE, 0.5,
     "fraction", t_lambda_fraction("mfstab-lanczos", "1")),
    (14, 4, "lambda_max (Lanczos), 2 threads: fraction of the limit per product", GE, 0.5,
     "fraction", t_lambda_fraction("mfstab-lanczos", "2")),
    (14, 4, "lambda_max (Lanczos), 1 thread: the same after its one-time storage build", GE, 0.5,
     "fraction", t_lambda_iter("1")),
    (14, 4, "lambda_max (Lanczos), 2 threads: the same after its one-time storage build", GE, 0.5,
     "fraction", t_lambda_iter("2")),
    (14, 4, "lambda_max, 1 thread: time / SciPy eigsh time", LE, 1.0, "ratio",
     t_lambda_vs_scipy("mfstab", "1")),
    (14, 4, "lambda_max (Lanczos), 1 thread: time / SciPy eigsh time", LE, 1.0, "ratio",
     t_lambda_vs_scipy("mfstab-lanczos", "1")),
    (14, 5, "the run's step: Gershgorin time / 300-product power time", LE, 1.0, "ratio", t_step),
    (14, 6, "assembly at 10^6 nodes: peak memory per entry of K", LE, 24, "B/nnz",
     t_assembly("bytes_per_nnz")),
    (14, 6, "assembly at 10^6 nodes: the CSR build's share of the assembly (beyond the numeric "
     "fill, CPU time)", LE, 0.2, "fraction",
     t_assembly("ratio")),
    (14, 7, "2 MPI ranks against one process: lambda_max", LE, 1e-10, "relative", t_mpi_error),
    (14, 8, "benchmark CSVs that state a physical limit", GE, 1.0, "share", t_limits),
    (15, 0, "10^6-particle file: read, plan and dt_gershgorin on one core", LE, 3.0, "s CPU",
     t_check_read),
]
for _th in ("1", "2"):
    TARGETS += [
        (15, 0, f"dt_certified / ARPACK lambda_max, 10^5, Gauss 2x2, lumped, {_th} thread(s)", LE,
         1.0, "ratio", t_certify("gauss2-perturb0-lumped", _th)),
        (15, 0, f"dt_certified / ARPACK lambda_max, 10^5, nodal perturbed, lumped, {_th} thread(s)",
         LE, 1.0, "ratio", t_certify("nodal-perturb0.2-lumped", _th)),
        (15, 0, f"dt_certified / ARPACK lambda_max, 10^5, nodal perturbed, consistent, {_th} "
         "thread(s)", LE, 1.0, "ratio", t_certify("nodal-perturb0.2-consistent", _th)),
    ]


def verdict(vals, cmp, target):
    ok = [(v <= target) if cmp == LE else (v >= target) for v in vals]
    if all(ok):
        return "met"
    med = statistics.median(vals)
    if (med <= target) if cmp == LE else (med >= target):
        return "median"
    return "no"


def fmt(v):
    return "" if v is None else f"{v:.4g}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", default="notebooks-data")
    ap.add_argument("-o", default=None)
    ap.add_argument("--markdown", default=None)
    a = ap.parse_args()
    out = []
    for issue, item, what, cmp, target, unit, fn in TARGETS:
        vals, ld, src = fn(a.data)
        vals = [v for v in vals if v is not None]
        row = {"issue": issue, "item": item or "", "quantity": what, "target": f"{cmp} {target:g}",
               "unit": unit, "runs": len(vals), "source": src}
        if vals:
            row.update(min=fmt(min(vals)), median=fmt(statistics.median(vals)),
                       max=fmt(max(vals)), met=verdict(vals, cmp, target))
        else:
            row.update(min="", median="", max="", met="not measured")
        row.update(load_min=fmt(min(ld)) if ld else "", load_max=fmt(max(ld)) if ld else "")
        out.append(row)
    # the other 2D families, per branch (informational rows: one process's repeats)
    fam, ld = t_disp_2d_branch(a.data)
    for name, (lo, med, hi) in fam:
        out.append({"issue": 14, "item": 3, "quantity": f"2D {name} dispersion per branch (ray)",
                    "target": "<= 60", "unit": "ns/point/branch", "runs": "repeats",
                    "min": fmt(lo), "median": fmt(med), "max": fmt(hi),
                    "load_min": fmt(min(ld)) if ld else "", "load_max": fmt(max(ld)) if ld else "",
                    "met": "met" if hi <= 60 else ("median" if med <= 60 else "no"),
                    "source": "bench_dispersion.csv phase=ray, seconds_* / (points branches)"})
    cols = ["issue", "item", "quantity", "target", "unit", "runs", "min", "median", "max",
            "load_min", "load_max", "met", "source"]
    path = a.o or os.path.join(a.data, "bench_acceptance.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        w.writerows(out)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("# Benchmark targets of issues 14 and 15\n\n"
                    "Generated by `analysis/bench/acceptance.py` from the committed "
                    "`notebooks-data/bench_*.csv` (do not edit by hand; rerun it after the "
                    "benchmarks). `met`: the target holds in every run; `median`: in the median "
                    "run only; `no`: not even there. `runs`: the repetitions of the CSV (each "
                    "a separate run side by side with its reference where the quantity is a "
                    "ratio); `repeats`: the repeats inside one process. The load columns are the "
                    "1-minute load average the runs saw (the machine has 2 cores and is shared).\n\n")
            f.write("| issue | item | quantity | target | unit | runs | min | median | max | load | met |\n")
            f.write("|---|---|---|---|---|---|---|---|---|---|---|\n")
            for r in out:
                load = f"{r['load_min']}-{r['load_max']}" if r["load_min"] else ""
                f.write(f"| {r['issue']} | {r['item']} | {r['quantity']} | {r['target']} | "
                        f"{r['unit']} | {r['runs']} | {r['min']} | {r['median']} | {r['max']} | "
                        f"{load} | {r['met']} |\n")
            f.write("\nSources (CSV and column of each row, in order):\n\n")
            for r in out:
                f.write(f"- {r['quantity']}: `{r['source']}`\n")
    print(f"wrote {path}" + (f" and {a.markdown}" if a.markdown else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
