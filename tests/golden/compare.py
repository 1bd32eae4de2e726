#!/usr/bin/python3
"""Compare two trees of mfstab outputs cell by cell (tests/test_golden.sh).

Numbers agree when |a - b| <= rtol * max(|a|, |b|) or |a - b| <= atol_col,
where atol_col = rtol * 1e-3 * max |x| over the column of the reference (values
that cancel to round-off, e.g. an omega2 of 1e-17 next to values of 4, are
compared on the column's scale); text cells must be equal.  Columns are
matched by name; renames.txt (old,new per line) maps renamed columns, and a
column that only the new output has is allowed (a new column is not a change
of behaviour).  tolerances.txt (column,rtol,atol per line) gives a column
its own tolerances where the algorithm promises less than rtol: values that
differ with the BLAS/LAPACK library (Debian's reference or OpenBLAS, chosen by
update-alternatives, docs/parallel.md) beyond 1e-12.  A whitespace-aligned table (reproduce's table.txt) is
compared field by field in the same way, where two numbers both below rtol in
magnitude (round-off of the table's O(1) quantities, 1e-15 or 0) are equal.  Prints one line per difference
(at most 20 per file) and the count; exit 1 on any difference.
usage: compare.py REFERENCE_DIR NEW_DIR [RTOL]"""
import csv, os, sys

def num(s):
    try:
        return float(s)
    except ValueError:
        return None

def close(a, b, rtol, atol):
    x, y = num(a), num(b)
    if x is None or y is None:
        return a == b
    return abs(x - y) <= rtol * max(abs(x), abs(y)) or abs(x - y) <= atol

def load_renames(path):
    ren = {}
    if os.path.exists(path):
        for line in open(path):
            line = line.strip()
            if line and not line.startswith('#'):
                old, new = line.split(',')
                ren[old] = new
    return ren

def load_tolerances(path):
    tol = {}
    if os.path.exists(path):
        for line in open(path):
            line = line.strip()
            if line and not line.startswith('#'):
                name, r, a = line.split(',')
                tol[name] = (float(r), float(a))
    return tol

def compare_csv(ref, new, rtol, ren, out, tols={}):
    r = list(csv.reader(open(ref, newline='')))
    n = list(csv.reader(open(new, newline='')))
    if not r or not n:
        return ['empty file'] if r != n else []
    rh, nh = r[0], n[0]
    idx = {}
    for k, name in enumerate(rh):
        want = ren.get(name, name)
        if want not in nh:
            out.append(f'column {name} missing')
            continue
        idx[k] = nh.index(want)
    if len(r) != len(n):
        out.append(f'{len(r) - 1} rows in the reference, {len(n) - 1} now')
        return out
    for k in idx:
        vals = [num(row[k]) for row in r[1:] if k < len(row)]
        scale = max([abs(v) for v in vals if v is not None] or [0.0])
        atol = rtol * 1e-3 * scale
        crtol = rtol
        if rh[k] in tols:
            crtol, catol = tols[rh[k]]
            atol = max(atol, catol)
        for i in range(1, len(r)):
            a, b = r[i][k], n[i][idx[k]]
            if not close(a, b, crtol, atol):
                out.append(f'row {i} column {rh[k]}: {a} -> {b}')
                if len(out) >= 20:
                    return out
    return out

def tiny(a, b, rtol):
    """Both numbers below rtol in magnitude: round-off of a table's O(1) quantities
    (the distance of two paths that agree, 1e-15 or 0), equal for the comparison."""
    x, y = num(a), num(b)
    return x is not None and y is not None and abs(x) <= rtol and abs(y) <= rtol

def compare_text(ref, new, rtol, out):
    r = open(ref).read().split('\n')
    n = open(new).read().split('\n')
    if len(r) != len(n):
        out.append(f'{len(r)} lines in the reference, {len(n)} now')
        return out
    for i, (a, b) in enumerate(zip(r, n)):
        fa, fb = a.split(), b.split()
        if len(fa) != len(fb) or not all(close(x, y, rtol, 0.0) or tiny(x, y, rtol)
                                         for x, y in zip(fa, fb)):
            out.append(f'line {i + 1}: "{a}" -> "{b}"')
    return out

def main():
    refdir, newdir = sys.argv[1], sys.argv[2]
    rtol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-12
    ren = load_renames(os.path.join(refdir, 'renames.txt'))
    tols = load_tolerances(os.path.join(refdir, 'tolerances.txt'))
    bad = files = 0
    for root, _, names in os.walk(refdir):
        for name in sorted(names):
            if name in ('renames.txt', 'tolerances.txt'):
                continue
            ref = os.path.join(root, name)
            rel = os.path.relpath(ref, refdir)
            new = os.path.join(newdir, rel)
            files += 1
            if not os.path.exists(new):
                print(f'{rel}: missing')
                bad += 1
                continue
            out = []
            if name.endswith('.csv'):
                compare_csv(ref, new, rtol, ren, out, tols)
            else:
                compare_text(ref, new, rtol, out)
            for line in out:
                print(f'{rel}: {line}')
            bad += len(out) > 0
    print(f'compare: {files} files, {bad} differ (rtol {rtol:g})')
    sys.exit(1 if bad else 0)

main()
