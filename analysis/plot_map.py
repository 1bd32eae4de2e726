#!/usr/bin/python3
"""Stable domains of a stretch map (`mfstab map --stretch-range ...`) in the plane of the principal
stretches, in the style of paper 000 Fig. 1: (a) the PDE's stable domain and the Lagrangian
kernel's; (b) the Lagrangian kernel's (dashed) and the Eulerian kernel's (solid), the states that
are stable for the PDE and unstable for the Eulerian kernel shaded; a panel per further Eulerian
frame (eulerian-consistent).  Made from the CSV only.

usage: /usr/bin/python3 analysis/plot_map.py MAP.csv OUT.png [TITLE]
Uses Debian's python3-matplotlib (and analysis/plot_figures.py's style)."""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

import findings as F  # noqa: E402
import plot_figures as P  # noqa: E402


def grids(rows):
    """{frame: (l1 values, l2 values, {(l1, l2): row})} of a stretch map."""
    out = {}
    for r in rows:
        g = out.setdefault(r["frame"], {})
        g[(float(r["lambda1"]), float(r["lambda2"]))] = r
    res = {}
    for fr, g in out.items():
        xs = sorted({k[0] for k in g})
        ys = sorted({k[1] for k in g})
        res[fr] = (xs, ys, g)
    return res


def field(xs, ys, g, f):
    """Z[j][i] = f(row at (xs[i], ys[j]))."""
    return [[f(g[(x, y)]) for x in xs] for y in ys]


def stable(r):
    return 1.0 if r["stable"] == "1" else 0.0


def pde(r):
    return 1.0 if r["pde_stable"] == "1" else 0.0


def boundary(ax, xs, ys, Z, what, line=0, **kw):
    """The boundary of {Z = 1} (the 0.5 contour of the indicator on the grid); a note in the
    panel where there is none (every grid state stable, or none)."""
    ones = sum(v == 1 for row in Z for v in row)
    if 0 < ones < len(Z) * len(Z[0]):
        ax.contour(xs, ys, Z, levels=[0.5], **kw)
    else:
        ax.text(0.03, 0.04 + 0.07 * line, f"{what}: {'every' if ones else 'no'} grid state stable",
                transform=ax.transAxes, fontsize=8, va="bottom",
                bbox={"facecolor": "white", "edgecolor": "0.7", "alpha": 0.9})


def plot(path, out, title=None):
    rows = list(csv.DictReader(open(path, newline="")))
    if not rows or "lambda1" not in rows[0]:
        sys.exit(f"{path}: not a stretch map of mfstab map")
    gr = grids(rows)
    frames = [f for f in ("lagrangian", "eulerian", "eulerian-consistent") if f in gr]
    first = rows[0]
    s = summary(rows)
    title = title or (f"Paper 000 Fig. 1: stable domains, material {first['material']}, "
                      f"{first['kernel']} {first['shape']}, D = {first['dilation']}, "
                      f"{first['quadrature']}, {first['lattice']} lattice, {first['mass']} mass, "
                      f"frames {', '.join(frames)}"
                      + (f", Eulerian kernel radius rule '{s['rule']}'" if s["rule"] else ""))
    npan = max(1, len(frames) - (1 if "lagrangian" in frames else 0)) + (1 if "lagrangian" in frames else 0)
    fig = P.Figure(1, npan, title, panel=(4.0, 3.6), legend_width=1.9)
    pan = 0
    xs, ys, g = gr[frames[0]]
    Zp = field(xs, ys, g, pde)
    pde_h = Line2D([], [], color="k", lw=2.2, label="PDE (acoustic tensor)")
    lag_h = Line2D([], [], color=P.COLOURS[0], ls="--", lw=1.8, label="Lagrangian kernel")
    if "lagrangian" in frames:
        ax = fig.axes[pan]
        xl, yl, gl = gr["lagrangian"]
        boundary(ax, xs, ys, Zp, "PDE", 1, colors="k", linewidths=2.2)
        boundary(ax, xl, yl, field(xl, yl, gl, stable), "Lagrangian", 0, colors=P.COLOURS[0],
                 linestyles="--", linewidths=1.8)
        ax.set_title(f"{P.letter(pan)}PDE and Lagrangian kernel")
        P.legend_right(ax, handles=[pde_h, lag_h])
        pan += 1
    for fr in [f for f in frames if f != "lagrangian"]:
        ax = fig.axes[pan]
        xe, ye, ge = gr[fr]
        Ze = field(xe, ye, ge, stable)
        shade = [[1.0 if ge[(x, y)]["pde_stable"] == "1" and ge[(x, y)]["stable"] != "1" else 0.0
                  for x in xe] for y in ye]
        ax.contourf(xe, ye, shade, levels=[0.5, 1.5], colors=[P.UNSTABLE], zorder=0)
        if "lagrangian" in gr:
            xl, yl, gl = gr["lagrangian"]
            boundary(ax, xl, yl, field(xl, yl, gl, stable), "Lagrangian", 1, colors=P.COLOURS[0],
                     linestyles="--", linewidths=1.8)
        boundary(ax, xe, ye, Ze, "Eulerian", 0, colors=P.COLOURS[1], linewidths=1.8)
        # the stable grid points themselves: the Eulerian domain is thin
        pts = [(x, y) for (x, y), r in ge.items() if r["stable"] == "1"]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], ls="none", marker="o", ms=2.5,
                color=P.COLOURS[1])
        sing = [(x, y) for (x, y), r in ge.items() if r["label"] == "singular"]
        if sing:
            ax.plot([p[0] for p in sing], [p[1] for p in sing], ls="none", marker="x", ms=3,
                    color="0.5")
        name = "Eulerian kernel (eq. 71)" if fr == "eulerian" else "Eulerian kernel (consistent)"
        ax.set_title(f"{P.letter(pan)}Lagrangian and {name}")
        hs = [lag_h] if "lagrangian" in gr else []
        hs += [Line2D([], [], color=P.COLOURS[1], lw=1.8, marker="o", ms=2.5, label=name),
               Patch(color=P.UNSTABLE, label="stable PDE,\nunstable Eulerian")]
        if sing:
            hs.append(Line2D([], [], ls="none", marker="x", color="0.5", label="MLS singular on\nthe current lattice"))
        P.legend_right(ax, handles=hs)
        pan += 1
    for ax in fig.axes:
        ax.set_xlabel(r"principal stretch $\lambda_1$")
        ax.set_ylabel(r"principal stretch $\lambda_2$")
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlim(min(xs), max(xs))
        ax.set_ylim(min(ys), max(ys))
    notes = []
    if "lagrangian" in gr:
        same = all(r["stable"] == r["pde_stable"] for r in rows if r["frame"] == "lagrangian")
        notes.append("(a) the Lagrangian kernel's boundary (dashed) is drawn over the PDE's (solid)"
                     + ("; they coincide: the same grid states are stable." if same else
                        "; where they differ the solid line shows."))
    notes.append("Grid: " + f"{len(xs)} x {len(ys)} stretch states; a boundary is the 0.5 contour between "
                 "stable and unstable grid states; the dots in (b), (c) are the Eulerian kernel's stable states.")
    d, name = os.path.split(out)
    fig.save(d or ".", name, s["paper"], s["ours"], notes)


def summary(rows):
    """Counts of the map for the caption: {paper, ours, rule}."""
    by = {}
    for r in rows:
        by.setdefault(r["frame"], []).append(r)
    any_frame = next(iter(by.values()))
    npde = sum(r["pde_stable"] == "1" for r in any_frame)
    parts = [f"{npde} of {len(any_frame)} grid states are stable for the PDE"]
    for fr, rr in by.items():
        st = sum(r["stable"] == "1" for r in rr)
        inside = sum(r["stable"] == "1" and r["pde_stable"] == "1" for r in rr)
        sing = sum(r["label"] == "singular" for r in rr)
        js = [float(r["J"]) for r in rr if r["stable"] == "1"]
        jr = f", J = {F.g(min(js))} to {F.g(max(js))}" if js and fr != "lagrangian" else ""
        parts.append(f"{fr}: {st} stable, {inside} of them within the PDE domain "
                     f"({F.g(inside / npde if npde else 0)} of it){jr}"
                     + (f", {sing} singular" if sing else ""))
    paper = ("The Lagrangian kernel's stable domain is almost indistinguishable from the PDE's; the "
             "Eulerian kernel's is markedly smaller (the shaded states are stable for the PDE and "
             "unstable for the Eulerian kernel).")
    rule = next((r["support_rule"] for r in rows if r["support_rule"]), "")
    return {"paper": paper, "ours": "; ".join(parts) + ".", "rule": rule}


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    plot(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else None)
