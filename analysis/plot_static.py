#!/usr/bin/python3
"""Convergence plots of paper 004 (Belytschko, Krongauz, Dolbow, Gerlach 1998) Figs 5-6 (beam)
and 8-9 (plate with a hole), made only from the CSV that `mfstab static --refine` writes
(analysis/static_studies.sh: static_beam.csv, static_plate.csv; with static_beam_gauss.csv the
Gauss-cell diagnostic of the paper's Fig. 11 idea).

usage: /usr/bin/python3 analysis/plot_static.py [DIR]
Writes DIR/static_beam.png, DIR/static_plate.png and DIR/static_beam_diagnostics.png (with
static_beam_ghost.csv and static_beam_gauss.csv) (Debian's python3-matplotlib).

Four panels per problem: the relative error in energy (eqs 118-119, 5 x 5 Gauss per background
cell: the paper's Figs 5 and 8), in energy at the nodes with the nodal volumes (the reading of
section 6.2.3 for Table III), in L2 (eqs 116-117: Figs 6 and 9) and the nodal l2 (eqs 114-115),
against the node spacing; the legend gives each method's rate fitted over all levels."""
import csv
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({
    "font.size": 10, "axes.titlesize": 10, "axes.labelsize": 10, "legend.fontsize": 8.5,
    "xtick.labelsize": 9, "ytick.labelsize": 9, "lines.linewidth": 1.5, "lines.markersize": 5,
    "axes.grid": True, "grid.alpha": 0.3, "legend.frameon": False, "savefig.facecolor": "white",
})
COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]
LINES = ["-", "--", "-.", ":", (0, (5, 1.5, 1, 1.5, 1, 1.5)), (0, (8, 2)), (0, (1, 1))]
MARKERS = ["o", "s", "^", "D", "v", "P", "X"]
ORDER = ["sph", "jb", "rl", "cd1", "cd2", "mls", "efg"]
NAMES = {"sph": "SPH (eq. 47)", "jb": "JB (eqs 49-52)", "rl": "RL (eqs 68-69)",
         "cd1": "CD1 (eqs 55-62)", "cd2": "CD2 (eqs 63-64)", "mls": "MLS nodal",
         "efg": "EFG 5x5 Gauss"}
PANELS = [("energy_error_norm", "rate_energy", "energy error (5x5 Gauss), relative"),
          ("energy_nodal_error_norm", "rate_energy_nodal", "energy error at the nodes, relative"),
          ("L2_error_norm", "rate_L2", "L2 error of u (5x5 Gauss), relative"),
          ("l2_error_norm", "rate_l2", "nodal l2 error of u^h(x_I), relative")]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def by_method(rows):
    """rows by method; a method run with another rule than its own (nodal; EFG: gauss5) is
    keyed method@rule"""
    out = {}
    for r in rows:
        own = "gauss5" if r["method"] == "efg" else "nodal"
        key = r["method"] if r["quadrature"] == own else r["method"] + "@" + r["quadrature"]
        out.setdefault(key, []).append(r)
    return out


def curves(ax, groups, col, rate):
    for i, k in enumerate([m for m in ORDER if m in groups] + sorted(k for k in groups if "@" in k)):
        g = groups[k]
        m = k.split("@")[0]
        name = NAMES[m] + (" (" + k.split("@")[1] + ")" if "@" in k else "")
        c = COLOURS[ORDER.index(m) % 7]
        ax.loglog([float(r["dx_m"]) for r in g], [float(r[col]) for r in g], color=c,
                  ls=LINES[ORDER.index(m) % 7], marker=MARKERS[ORDER.index(m) % 7], mfc="white",
                  label=f"{name}: {float(g[0][rate]):.2f}")
    ax.set_xlabel("node spacing dx (m); finer to the right")
    ax.invert_xaxis()
    ax.legend(title="method: rate over all levels", loc="center left", bbox_to_anchor=(1.0, 0.5))


def config_line(r0, what):
    return (f"kernel {r0['kernel']}, support radius a = {float(r0['dilation']):.4g} dx, "
            f"E = {float(r0['young_pa']):g} Pa, nu = {float(r0['poisson']):g}, "
            f"{'plane strain' if r0['plane_strain'] == '1' else 'plane stress'}, {what}")


def save(fig, d, png, sup, cap_items):
    fig.suptitle("\n".join(textwrap.wrap(sup, 150)), fontsize=11)
    cap = []
    for head, text in cap_items:
        cap += textwrap.wrap(text, 190, initial_indent=head, subsequent_indent="    ")
    fig.text(0.01, 0.01, "\n".join(cap), fontsize=9, va="bottom", ha="left")
    fig.tight_layout(rect=(0, 0.03 + 0.022 * len(cap), 1, 0.95))
    fig.savefig(os.path.join(d, png), dpi=110)
    plt.close(fig)


def plot(d, csv_name, png, title, claims):
    rows = read(os.path.join(d, csv_name))
    groups = by_method(rows)
    fig, axes = plt.subplots(2, 2, figsize=(12.5, 8.6))
    for ax, (col, rate, label) in zip(axes.ravel(), PANELS):
        curves(ax, groups, col, rate)
        ax.set_ylabel(label)
    r0 = rows[0]
    ebc = "Lagrange multipliers on Gamma_u" if r0["ebc"] == "lm" else "ghost columns at x <= 0"
    save(fig, d, png, f"{title} -- " + config_line(r0, ebc + "; nodal quadrature except EFG"),
         claims(groups))


def diagnostics(d):
    """The beam without an essential boundary (--ebc ghost) and with Gauss cells instead of
    nodal quadrature (--quadrature gauss5): what limits the nodal methods."""
    ghost, gauss = (os.path.join(d, n) for n in ("static_beam_ghost.csv", "static_beam_gauss.csv"))
    if not (os.path.exists(ghost) and os.path.exists(gauss)):
        return
    gh, ga = by_method(read(ghost)), by_method(read(gauss))
    fig, axes = plt.subplots(2, 2, figsize=(12.5, 8.6))
    for ax, g, (col, rate, label), what in [(axes[0, 0], gh, PANELS[0], "--ebc ghost"),
                                            (axes[0, 1], gh, PANELS[2], "--ebc ghost"),
                                            (axes[1, 0], ga, PANELS[0], "--quadrature gauss5, multipliers"),
                                            (axes[1, 1], ga, PANELS[2], "--quadrature gauss5, multipliers")]:
        curves(ax, g, col, rate)
        ax.set_ylabel(label)
        ax.set_title(what)
    lam = 1.013722
    cd1 = float(gh["cd1"][-1]["L2_error_norm"]) if "cd1" in gh else float("nan")
    save(fig, d, "static_beam_diagnostics.png",
         "Paper 004, beam: the nodal methods without an approximated essential boundary (top) and "
         "with 5 x 5 Gauss cells (bottom) -- " + config_line(read(ghost)[0], f"dx = 1/2 .. {float(read(ghost)[-1]['dx_m']):g} (top), .. {float(read(gauss)[-1]['dx_m']):g} (bottom)"),
         [("Paper (section 6.2.3, Fig. 11): ",
           "with background quadrature the corrected derivative and MLS approximations show excellent "
           "convergence; the low accuracy of the nodal methods is attributed to nodal integration."),
          ("mfstab: ",
           f"without the essential boundary MLS converges (energy {float(gh['mls'][0]['rate_energy']):.2f}) "
           f"and CD1, CD2 stall at L2 {cd1:.4%} = 1 - 1/lambda ({1 - 1 / lam:.4%}, lambda = {lam} the Shepard "
           "test gradient at the nodes: docs/errata.md E15); with Gauss cells CD2 converges (L2 "
           f"{float(ga['cd2@gauss5'][0]['rate_L2']):.2f}), CD1 with its Shepard values on Gamma_u stalls at "
           f"{float(ga['cd1@gauss5'][-1]['L2_error_norm']):.2%}.")])


def rate(groups, m, col):
    return float(groups[m][0][col]) if m in groups else float("nan")


def finest(groups, m, col):
    return float(groups[m][-1][col]) if m in groups else float("nan")


def beam_claims(g):
    return [("Paper (Table III, Figs 5-6): ",
             "SPH and JB do not converge; RL 0.x; CD1, CD2, MLS about 1.x in energy and 1.x in L2; EFG "
             "1.x in energy, 2.x in L2 (decimals lost in the extraction)."),
            ("mfstab: ",
             f"EFG energy {rate(g, 'efg', 'rate_energy'):.2f}, L2 {rate(g, 'efg', 'rate_L2'):.2f}; "
             f"MLS {rate(g, 'mls', 'rate_energy'):.2f} / {rate(g, 'mls', 'rate_L2'):.2f}; CD1 and CD2 "
             f"stall at L2 {finest(g, 'cd1', 'L2_error_norm'):.2%} and {finest(g, 'cd2', 'L2_error_norm'):.2%} "
             "(Shepard test gradients: lambda = 1.0137, docs/errata.md E15); SPH energy error "
             f"{finest(g, 'sph', 'energy_error_norm'):.2f} and JB {finest(g, 'jb', 'energy_error_norm'):.2f} at "
             "the finest level: no convergence in energy.")]


def plate_claims(g):
    return [("Paper (Table III, Figs 8-9): ",
             "rates much lower than on the beam (non-uniform nodes, Fig. 7 lost); EFG 1.x in energy and "
             "2.x in L2; CD1, CD2, MLS 0.x in energy and 1.x in L2; SPH, JB do not converge."),
            ("mfstab (quasi-uniform lattice nodes): ",
             f"EFG energy {rate(g, 'efg', 'rate_energy'):.2f}, L2 {rate(g, 'efg', 'rate_L2'):.2f}; "
             f"MLS {rate(g, 'mls', 'rate_energy'):.2f} / {rate(g, 'mls', 'rate_L2'):.2f}, CD1 "
             f"{rate(g, 'cd1', 'rate_energy'):.2f} / {rate(g, 'cd1', 'rate_L2'):.2f}, CD2 "
             f"{rate(g, 'cd2', 'rate_energy'):.2f} / {rate(g, 'cd2', 'rate_L2'):.2f}; SPH "
             f"{rate(g, 'sph', 'rate_energy'):.2f}, JB {rate(g, 'jb', 'rate_energy'):.2f}, RL "
             f"{rate(g, 'rl', 'rate_energy'):.2f} in energy.")]


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "notebooks-data"
    if os.path.exists(os.path.join(d, "static_beam.csv")):
        plot(d, "static_beam.csv", "static_beam.png",
             "Paper 004 Figs 5-6: cantilever beam, L = 8, D = 1", beam_claims)
    diagnostics(d)
    if os.path.exists(os.path.join(d, "static_plate.csv")):
        plot(d, "static_plate.csv", "static_plate.png",
             "Paper 004 Figs 8-9: quarter plate with a hole, a = 1, b = 5", plate_claims)


if __name__ == "__main__":
    main()
