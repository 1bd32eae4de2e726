#!/usr/bin/python3
"""Dispersion after the plan, mfstab against NumPy, side by side (issue 14 item 3).

The same relations at the same points, each run timing both one after the
other (the machine is shared: a run's ratio compares like with like):
  1d  paper 003 eq. 74, Eulerian nodal, quartic MLS, D = 1.5, 2.5, five stresses,
      1000 wave numbers on [0, 1]:
        omega2 = (1 + s) S^2 - s (P - S^2),  S = sum_j phi'(j) sin(k j),
        P = sum_j phi''(j) (1 - cos(k j))
      NumPy "per-stress": the sums for each (D, stress), as the C ray at one
      stress (mfs_disp_ray, phase "ray"); "shared": S and P once per D and
      broadcast over the stresses, as the C ray over all the stresses at once
      (phase "ray-stresses").
  2d  eq. 118, anti-plane, cubic MLS, D = 2, stress-tri, 8 angles x 400 wave
      numbers: omega2 = sum_jk K_jk cos(k . (j a1 + k a2)) / M_00 (the stencil of
      mfstab stencil), against the C ray (phase "ray").
The coefficients (phi', phi'', K_jk) and the C values come from
bench_dispersion --numpy-data (once per family); NumPy evaluates from them
(vectorized: np.sin, np.cos of the phase matrices and a matrix product), the
time after the plan as for the C side.  The C side is timed in this process:
bench_dispersion.c built as a module (bench_dispersion_py.so, ctypes; the same
families and phases as the executable), because the machine runs each process
at one of two speed levels (docs/benchmarks.md, round 8) and a C subprocess
per run compared one level with the other.  Each run: 7 C passes and 7
NumPy passes in turns (C, NumPy, C, ...), each side's first pass untimed, and
the median of each side (the C rays of a family take 34-130 us: with all C
repeats before all NumPy ones, a burst of another process's work of about a
millisecond fell on one side only, and one run in seven moved by 25-35 %);
over --runs N (>= 5) runs, min /
median / max of each and of the ratio NumPy / C; the load average (1 min) at
every run.
CSV (default notebooks-data/bench_dispersion_numpy.csv):
  family,comparison,run,c_ns_per_point,numpy_ns_per_point,ratio,numpy_error,load1,
  flop_per_point
with rows run = min, median, max after the runs; numpy_error the largest
|NumPy - C| over the largest |C| omega2; flop_per_point the minimal work of a
point, the C phase's gflop (bench_dispersion: the folded lattice sums once per
wave vector, shared by the stresses) over its points, the same for both sides
(analysis/bench/limits.py states it against dgemm's rate: fraction for the C
side, numpy_fraction for NumPy).
usage: /usr/bin/python3 analysis/bench/bench_dispersion_numpy.py [--runs N]
       [--bench PATH] [--module PATH] [-o FILE]
Not a test: nothing asserts a time."""
import argparse
import csv
import ctypes
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np


REPS = 7  # repeats per run and side, alternating C, NumPy, C, ... (each side: the median of 7)


def load1():
    with open('/proc/loadavg') as f:
        return float(f.read().split()[0])


def c_data(bench, family, tmp):
    """The family's coefficients and C values into tmp; flop per point of each phase."""
    out = subprocess.run([bench, '--family', family, '--repeat', '1', '--no-threads',
                          '--numpy-data', tmp], check=True, capture_output=True, text=True).stdout
    return {r['phase']: 1e9 * float(r['gflop']) / float(r['points'])
            for r in csv.DictReader(io.StringIO(out))}


def c_module(path):
    """bench_dispersion_ns(family, phase, 1): one C pass in ns per point (after its untimed one)."""
    lib = ctypes.CDLL(path)
    f = lib.bench_dispersion_ns
    f.restype = ctypes.c_double
    f.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int]
    return lambda family, phase: f(family.encode(), phase.encode(), 1)


def side_by_side(c, numpy_f, npts):
    """The medians (ns per point) of REPS C passes and REPS NumPy passes, taken in turns, so
    that a burst of another process's work falls on both sides alike; NumPy's first pass
    untimed, as C's (bench_dispersion_ns makes one before it times)."""
    numpy_f()
    cs, ns = [], []
    for _ in range(REPS):
        cs.append(c())
        t0 = time.perf_counter()
        numpy_f()
        ns.append(1e9 * (time.perf_counter() - t0) / npts)
    return statistics.median(cs), statistics.median(ns)


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def numpy_1d(tmp):
    coef, val = read(os.path.join(tmp, '1d_coef.csv')), read(os.path.join(tmp, '1d_values.csv'))
    dils = np.unique(coef['dilation'])
    sig = np.unique(val['sigma'])
    kap = np.unique(val['kappa'])
    k = kap * np.pi
    terms = [(coef['j'][coef['dilation'] == D], coef['dphi'][coef['dilation'] == D],
              coef['d2phi'][coef['dilation'] == D]) for D in dils]

    def per_stress():
        out = []
        for j, d1, d2 in terms:
            for s in sig:
                X = np.outer(k, j)
                S = np.sin(X) @ d1
                P = (1.0 - np.cos(X)) @ d2
                out.append((1.0 + s) * S * S - s * (P - S * S))
        return np.concatenate(out)

    def shared():
        out = []
        for j, d1, d2 in terms:
            X = np.outer(k, j)
            S = np.sin(X) @ d1
            P = (1.0 - np.cos(X)) @ d2
            out.append(((1.0 + sig[:, None]) * S * S - sig[:, None] * (P - S * S)).ravel())
        return np.concatenate(out)

    # the C file's order: dilation, sigma, theta, kappa
    ref = val['omega2']
    err = max(np.max(np.abs(per_stress() - ref)), np.max(np.abs(shared() - ref)))
    return {'per-stress': per_stress, 'shared': shared}, len(ref), err / np.max(np.abs(ref))


def numpy_2d(tmp):
    coef, val = (read(os.path.join(tmp, '2d-antiplane_coef.csv')),
                 read(os.path.join(tmp, '2d-antiplane_values.csv')))
    j, kk, K = coef['j'], coef['k'], coef['K']
    M00 = np.sum(coef['M'][(j == 0) & (kk == 0)])
    ths = np.unique(val['theta'])
    kaps = [val['kappa'][val['theta'] == t] for t in ths]  # the C file's order: theta, kappa

    def bloch():
        out = []
        for t, kap in zip(ths, kaps):
            ph = np.outer(kap * np.pi * np.cos(t), j) + np.outer(kap * np.pi * np.sin(t), kk)
            out.append(np.cos(ph) @ K / M00)
        return np.concatenate(out)

    ref = val['omega2']
    return {'bloch': bloch}, len(ref), np.max(np.abs(bloch() - ref)) / np.max(np.abs(ref))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser()
    ap.add_argument('--runs', type=int, default=7)
    ap.add_argument('--bench', default=os.path.join(root, 'build', 'analysis', 'bench',
                                                    'bench_dispersion'))
    ap.add_argument('--module', default=os.path.join(root, 'build', 'analysis', 'bench',
                                                     'bench_dispersion_py.so'))
    ap.add_argument('-o', default=os.path.join(root, 'notebooks-data',
                                               'bench_dispersion_numpy.csv'))
    a = ap.parse_args()
    if a.runs < 5:
        sys.exit('--runs %d: at least 5' % a.runs)
    # comparisons: (family, NumPy variant, C phase)
    comps = [('1d', 'per-stress', 'ray'), ('1d', 'shared', 'ray-stresses'), ('2d-antiplane', 'bloch', 'ray')]
    rows = []
    c_ns = c_module(a.module)
    with tempfile.TemporaryDirectory() as tmp:
        data = {}
        for fam in ('1d', '2d-antiplane'):
            d = os.path.join(tmp, fam)
            os.mkdir(d)
            fpp = c_data(a.bench, fam, d)
            data[fam] = (fpp,) + (numpy_1d if fam == '1d' else numpy_2d)(d)
        for run in range(1, a.runs + 1):
            for fam in ('1d', '2d-antiplane'):
                l = load1()
                fpp, fns, npts, err = data[fam]
                for f, variant, phase in comps:
                    if f != fam:
                        continue
                    cns, nns = side_by_side(lambda: c_ns(fam, phase), fns[variant], npts)
                    rows.append([fam, '%s/%s' % (variant, phase), run, cns, nns, nns / cns,
                                 err, l, fpp[phase]])
    summary = []
    for f, variant, phase in comps:
        name = '%s/%s' % (variant, phase)
        rs = [r for r in rows if r[0] == f and r[1] == name]
        for what, fn in (('min', min), ('median', statistics.median), ('max', max)):
            summary.append([f, name, what, fn(r[3] for r in rs), fn(r[4] for r in rs),
                            fn(r[5] for r in rs), max(r[6] for r in rs), fn(r[7] for r in rs),
                            rs[0][8]])
    os.makedirs(os.path.dirname(os.path.abspath(a.o)), exist_ok=True)
    with open(a.o, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['family', 'comparison', 'run', 'c_ns_per_point', 'numpy_ns_per_point', 'ratio',
                    'numpy_error', 'load1', 'flop_per_point'])
        for r in rows + summary:
            w.writerow([r[0], r[1], r[2], '%.4g' % r[3], '%.4g' % r[4], '%.4g' % r[5], '%.3g' % r[6],
                        '%.2f' % r[7], '%.6g' % r[8]])
    print('%-14s %-24s %-6s %10s %12s %8s %10s %6s' % ('family', 'numpy/C phase', 'run', 'C ns/pt',
                                                       'NumPy ns/pt', 'ratio', 'error', 'load'))
    for r in summary:
        print('%-14s %-24s %-6s %10.4g %12.4g %8.3g %10.2g %6.2f' % tuple(r[:8]))
    print('wrote %s' % a.o)


if __name__ == '__main__':
    main()
