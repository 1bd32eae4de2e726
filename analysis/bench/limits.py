#!/usr/bin/python3
"""The physical limit of each row of a benchmark CSV (issue 14 item 8).

    limits.py CSV [--rule NAME] [--gbs G1 --gbs2 G2 --gflops F] [--bandwidth FILE]

adds (or refills) three columns in place: limit_kind (bytes: the bytes the
row's work must move at least once, at the measured memory bandwidth; flops:
the flops it must do, at the measured dgemm rate; none: no lower bound is
derived for that work, the cells empty), limit_s (seconds at the limit) and
fraction (limit_s / the row's seconds).  G1 and G2 are the bandwidths (GB/s)
of one and two threads, F the flop rate (Gflop/s) of one thread, from
notebooks-data/bench_bandwidth.csv (analysis/bench/bench_bandwidth.c; --bandwidth
FILE, default the repository's, read when --gbs is not given).  --rule NAME
(bench_eigs, ...) when the file name is not the benchmark's.  What
each benchmark's limit counts is in docs/benchmarks.md; the rules are below,
one function per CSV, chosen by the file name.  bench_lambda.csv and
bench_assembly.csv compute their limits themselves (bench_lambda.c,
bench_assembly.c): for them only limit_kind is filled where missing.  Two
CSVs get a second fraction for a second time of the same work:
bench_table4's cd1_fraction, bench_dispersion_numpy's numpy_fraction.
"""
import argparse
import csv
import os
import sys


def f(row, key):
    v = row.get(key, "")
    try:
        return float(v)
    except ValueError:
        return None


def half_matvec_bytes(n, nnz):
    """mfs_eig_max's product: the diagonal and strict upper triangle (12 B per
    entry: value and int column), 8 B row pointers, diagonal, x, y."""
    return 6.0 * (nnz - n) + 8.0 * (n + 1) + 24.0 * n


def full_matvec_bytes(n, nnz, ptr=8.0, vectors=3):
    """A CSR product over full rows: 12 B per entry, the row pointers, and
    `vectors` vectors of n doubles (x, y, and the scaling when it is applied
    on the fly)."""
    return 12.0 * nnz + ptr * (n + 1) + 8.0 * vectors * n


def eigs(row, bw):
    n, nnz, mv, s = f(row, "dofs"), f(row, "nnz_K"), f(row, "matvecs"), f(row, "seconds")
    if row["phase"] == "eigs" and n and nnz and mv:
        # op_bytes: what the stored operator's product reads (mfs_eig_info.op_bytes);
        # rows without it are from the scalar half storage of before (12 B per entry)
        ob = f(row, "op_bytes")
        return "bytes", mv * (ob if ob else half_matvec_bytes(n, nnz)) / bw[1], s
    if row["phase"] == "eigsh" and n and nnz and mv:  # SciPy: int32 indptr, x and y
        return "bytes", mv * full_matvec_bytes(n, nnz, 4.0, 2) / bw[1], s
    if row["phase"] == "setup" and n and nnz:  # K written once (assembly)
        return "bytes", full_matvec_bytes(n, nnz, 8.0, 0) / bw[1], s
    return "none", None, s


def blas(row, bw):
    n, nnz, mv = f(row, "dofs"), f(row, "nnz_K"), f(row, "matvecs")
    return "bytes", mv * half_matvec_bytes(n, nnz) / bw[1], f(row, "eig_s")


def mpi(row, bw):
    mv, s = f(row, "matvecs"), f(row, "eig_s")
    ranks = int(f(row, "ranks") or 1)
    if row["mode"] == "serial":
        n, nnz = f(row, "dofs"), f(row, "nnz_max")
        return "bytes", mv * half_matvec_bytes(n, nnz) / bw[1], s
    # each rank its full rows scaled on the fly (mfs_peigs); the busiest rank,
    # at the bandwidth of as many threads as ranks (one memory bus)
    rows, nnz = f(row, "rows_max"), f(row, "nnz_max")
    return "bytes", mv * full_matvec_bytes(rows, nnz) / bw[min(ranks, 2)], s


def static(row, bw):
    nnz, fac, s = f(row, "nnz_K"), f(row, "factor_nnz"), f(row, "total_s")
    if nnz is None or fac is None:
        return "none", None, s
    # K written once and read once by the factorization, the factor written once
    return "bytes", (24.0 * nnz + 12.0 * fac) / bw[1], s


def solver(row, bw):
    """1D EFG, nodal integration, leapfrog: per particle and step the state
    (u and v read and written: 32 B) and the plan's gradient row (12 B per
    neighbour: value and index; 2 floor(D) + 1 neighbours)."""
    p, steps, d, s = f(row, "particles"), f(row, "steps"), f(row, "dilation"), f(row, "seconds")
    nb = 2 * int(d) + 1
    return "bytes", p * steps * (32.0 + 12.0 * nb) / bw[1], s


def check(row, bw, gflops):
    """bench_check: the factorizations of sigma M - K (all that follows the
    estimate, and the numeric factorizations alone), CHOLMOD's flops at the
    one-thread dgemm rate; the other phases have no limit derived."""
    g, s = f(row, "gflop"), f(row, "seconds")
    if row.get("phase") in ("factorizations", "numeric") and g:
        return "flops", g * 1e9 / gflops, s  # gflop: 10^9 flops
    return "none", None, s


def table4(row, bw, gflops):
    """bench_static table4: the MLS shape functions with their gradients at a
    point with n neighbours, the operation count of the paper's Table II,
    n C_w + 101 n + 32 flops (C_w = 20: a kernel with its gradient; the
    moment matrix, its derivatives and the solves), at dgemm's one-thread
    rate; the corrected derivatives (cd1) n C_w + 28 n + 10 flops, into the
    extra column cd1_fraction.  Per point: the columns are microseconds per
    point."""
    n, tm, tk = f(row, "mean_neighbours"), f(row, "mls_us_per_point"), f(row, "cd1_us_per_point")
    if n is None or not tm:
        return "none", None, None
    if tk:
        row["cd1_fraction"] = f"{(20.0 * n + 28.0 * n + 10.0) / gflops / (tk * 1e-6):.4f}"
    return "flops", (20.0 * n + 101.0 * n + 32.0) / gflops, tm * 1e-6


def dispersion(row, bw, gflops):
    """bench_dispersion: the folded lattice sums once per wave vector (the
    gflop column, bench_dispersion.c), at dgemm's one-thread rate times the
    row's threads; the phases, the eigen solves and the reference path's
    extra sums are work above that bound."""
    g, s, t = f(row, "gflop"), f(row, "seconds_median"), f(row, "threads") or 1.0
    if g:
        return "flops", g * 1e9 / (gflops * t), s
    return "none", None, s


def dispersion_numpy(row, bw, gflops):
    """bench_dispersion_numpy: per point (the columns are ns per point) the
    C phase's minimal work (flop_per_point: bench_dispersion's gflop over its
    points, the folded sums once per wave vector), at dgemm's one-thread
    rate, against c_ns_per_point; the same flops against numpy_ns_per_point
    into the extra column numpy_fraction."""
    fpp, tc, tn = f(row, "flop_per_point"), f(row, "c_ns_per_point"), f(row, "numpy_ns_per_point")
    row["numpy_fraction"] = ""
    if not fpp:
        return "none", None, None
    lim = fpp / gflops
    if tn:
        row["numpy_fraction"] = f"{lim / (tn * 1e-9):.4f}"
    return "flops", lim, tc * 1e-9 if tc else None


def dispersion_map(row, bw, gflops):
    """bench_map, bench_map_command: the stability map's lattice sums (the
    gflop column: bench_map.c counts them point by point, 2 flops per folded
    offset and component at every wave vector sample whose sums a grid point
    evaluates, the Lagrangian zone samples' once), at dgemm's one-thread rate
    times the row's threads, against total_s (bench_map) or wall_s (the
    command)."""
    g, t = f(row, "gflop"), f(row, "threads") or 1.0
    s = f(row, "total_s") if f(row, "total_s") is not None else f(row, "wall_s")
    if g:
        return "flops", g * 1e9 / (gflops * t), s
    return "none", None, s


def step(row, bw):
    """bench_step: the Gershgorin bound max_i sum_j |K_ij| / m_i is one pass
    over K's stored entries (nnz_K: 8 B per value; the column indices are not
    needed for row sums), its row pointers (8 B) and the masses (8 B per
    unknown); the power rule 300 products with K (12 B per entry, 8 B per row
    pointer, x read, y written and the mass scaling read: 3 vectors), at the
    one-thread bandwidth.  The rod's rules work from the plan (K not stored):
    its limit is the same work with K stored.  The certified rule
    (factorizations) has no limit derived: its flop count is not in the CSV."""
    n, nnz, s = f(row, "dofs"), f(row, "nnz_K"), f(row, "seconds_median")
    if not (n and nnz):
        return "none", None, s
    if row["rule"] == "gershgorin":
        return "bytes", (8.0 * nnz + 8.0 * (n + 1) + 8.0 * n) / bw[1], s
    if row["rule"] == "power":
        return "bytes", POWER_ITERATIONS * full_matvec_bytes(n, nnz) / bw[1], s
    return "none", None, s


POWER_ITERATIONS = 300  # lib/time/mfs_solver.c, mfs_solver2d.c


def first_touch(row, bw):
    """bench_first_touch: the block's bytes written once at the one-thread
    bandwidth, against first_touch_s (the page faults; the rewrite_s column
    is the same bytes once mapped)."""
    mb, s = f(row, "size_mb"), f(row, "first_touch_s")
    if not mb:
        return "none", None, s
    return "bytes", mb * 1048576.0 / bw[1], s


def phases(row, bw):
    """bench_phases: each row's bytes (the Lanczos call's products, its
    products alone, the read of as many bytes) at the one-thread bandwidth;
    the compute rows move no memory: none."""
    b, s = f(row, "bytes"), f(row, "seconds")
    if not b:
        return "none", None, s
    return "bytes", b / bw[1], s


def none(row, bw):
    for k in ("seconds", "total_s", "wall_s", "seconds_median", "eval_s"):
        if f(row, k) is not None:
            return "none", None, f(row, k)
    return "none", None, None


RULES = {
    "bench_eigs": eigs,
    "bench_blas": blas,
    "bench_mpi": mpi,
    "bench_mpi_loaded": mpi,
    "bench_static": static,
    "bench_solver": solver,
    "bench_check": check,
    "bench_step": step,
    "bench_first_touch": first_touch,
    "bench_phases": phases,
}
OWN = ("bench_lambda", "bench_assembly", "bench_bandwidth")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("--rule")
    ap.add_argument("--gbs", type=float)
    ap.add_argument("--gbs2", type=float)
    ap.add_argument("--gflops", type=float)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--bandwidth",
                    default=os.path.join(here, "..", "..", "notebooks-data", "bench_bandwidth.csv"))
    a = ap.parse_args()
    if a.gbs is None:
        try:
            with open(a.bandwidth, newline="") as fh:
                lim = {r["threads"]: r for r in csv.DictReader(fh) if r["kernel"] == "limit"}
            a.gbs, a.gbs2 = float(lim["1"]["gbs"]), float(lim["2"]["gbs"])
            a.gflops = float(lim["1"]["gflops"])
        except (OSError, KeyError, ValueError):
            print(f"limits.py: no limits (give --gbs, --gbs2, --gflops or a {a.bandwidth} "
                  "from analysis/bench/bench_bandwidth); the CSV is left as it is", file=sys.stderr)
            return 0
    name = a.rule or os.path.splitext(os.path.basename(a.csv))[0]
    with open(a.csv, newline="") as fh:
        lines = [l for l in fh if not l.startswith("#")]
    rows = list(csv.DictReader(lines))
    if not rows:
        return 0
    cols = list(rows[0].keys())
    if name == "bench_bandwidth":
        return 0
    bw = {1: a.gbs * 1e9, 2: a.gbs2 * 1e9}
    if name in OWN or name.startswith("bench_lambda_"):  # bench_lambda_run2 ...: bench_lambda's rows
        if "limit_kind" not in cols:
            cols.append("limit_kind")
        for r in rows:
            if not r.get("limit_kind"):
                r["limit_kind"] = "bytes" if r.get("limit_s") else "none"
    else:
        rule = RULES.get(name, none)
        if rule is check:
            rule = lambda r, b: check(r, b, a.gflops * 1e9)  # noqa: E731
        if name == "bench_dispersion":
            rule = lambda r, b: dispersion(r, b, a.gflops * 1e9)  # noqa: E731
        if name in ("bench_map", "bench_map_command"):
            rule = lambda r, b: dispersion_map(r, b, a.gflops * 1e9)  # noqa: E731
        if name == "bench_dispersion_numpy":
            rule = lambda r, b: dispersion_numpy(r, b, a.gflops * 1e9)  # noqa: E731
            if "numpy_fraction" not in cols:
                cols.append("numpy_fraction")
        if name == "bench_table4":
            rule = lambda r, b: table4(r, b, a.gflops * 1e9)  # noqa: E731
            if "cd1_fraction" not in cols:
                cols.append("cd1_fraction")
        for c in ("limit_kind", "limit_s", "fraction"):
            if c not in cols:
                cols.append(c)
        for r in rows:
            try:
                kind, lim, secs = rule(r, bw)
            except (TypeError, ZeroDivisionError):  # a summary row, or a cell missing
                kind, lim, secs = "none", None, None
            r["limit_kind"] = kind
            r["limit_s"] = "" if lim is None else f"{lim:.6g}"
            r["fraction"] = "" if lim is None or not secs else f"{lim / secs:.4f}"
    tmp = a.csv + ".tmp"
    with open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, a.csv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
