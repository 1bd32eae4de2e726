#!/usr/bin/python3
"""Plots of the reproduced figures, made only from the CSV files that
`mfstab reproduce` writes (default directory notebooks-data/).

usage: /usr/bin/python3 analysis/plot_figures.py [DIR]
Uses Debian's python3-matplotlib; writes DIR/figNN.png next to the CSV."""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def curves(rows, key):
    """Group rows into curves keyed by key(row) -> (kappa list, omega2 list)."""
    out = defaultdict(lambda: ([], []))
    for r in rows:
        k, w = out[key(r)]
        k.append(float(r["kappa"]))
        w.append(float(r["omega2"]))
    return out


def panel(ax, rows, key, title, label):
    for name, (k, w) in sorted(curves(rows, key).items()):
        ax.plot(k, w, label=label(name))
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(r"$\kappa\Delta x/\pi$")
    ax.set_ylabel(r"$(\omega\Delta x/c)^2$")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)


def by_dilation(d, path, out, title, key, label):
    rows = read(os.path.join(d, path))
    dils = sorted({r["dilation"] for r in rows}, key=float)
    fig, axes = plt.subplots(1, len(dils), figsize=(5 * len(dils), 4), squeeze=False)
    for ax, dil in zip(axes[0], dils):
        panel(ax, [r for r in rows if r["dilation"] == dil], key, f"{title}, D = {dil}", label)
    fig.tight_layout()
    fig.savefig(os.path.join(d, out), dpi=110)
    plt.close(fig)


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "notebooks-data"
    sig = lambda r: float(r["sigma"])  # noqa: E731
    by_dilation(d, "fig03.csv", "fig03.png", "Fig 3: Eulerian kernel, nodal, quartic MLS", sig,
                lambda s: rf"$\bar\sigma$ = {s:g}")
    by_dilation(d, "fig04.csv", "fig04.png", "Fig 4: Eulerian, nodal, sbar = -1", sig,
                lambda s: rf"$\bar\sigma$ = {s:g}")
    by_dilation(d, "fig09.csv", "fig09.png", "Fig 9: Eulerian kernel, stress points", sig,
                lambda s: rf"$\bar\sigma$ = {s:g}")
    # Fig 10: all dilations in one panel with the linear finite element
    rows = read(os.path.join(d, "fig10.csv"))
    fem = read(os.path.join(d, "fig10_fem.csv"))
    fig, ax = plt.subplots(figsize=(5.5, 4))
    panel(ax, rows, lambda r: float(r["dilation"]),
          "Fig 10: Lagrangian kernel, stress points, cubic MLS", lambda s: f"D = {s:g}")
    k = [float(r["kappa"]) for r in fem]
    ax.plot(k, [float(r["omega2"]) for r in fem], "k--", label="linear FE (MLS D = 1, gauss2)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig10.png"), dpi=110)
    plt.close(fig)
    # Fig 11: least-squares stabilization, one panel per dilation
    rows = []
    for a in ("0", "0.001", "0.01", "0.1"):
        for r in read(os.path.join(d, f"fig11_alpha{a}.csv")):
            r["alpha"] = a
            rows.append(r)
    dils = sorted({r["dilation"] for r in rows}, key=float)
    fig, axes = plt.subplots(1, len(dils), figsize=(10, 4))
    for ax, dil in zip(axes, dils):
        panel(ax, [r for r in rows if r["dilation"] == dil], lambda r: float(r["alpha"]),
              f"Fig 11: least-squares stabilized nodal, D = {dil}", lambda a: rf"$\alpha_s$ = {a:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig11.png"), dpi=110)
    plt.close(fig)
    # 2D figures: one curve per angle and branch
    for name, files, titles in (
        ("fig13", ["fig13.csv"], ["nodal"]),
        ("fig14", ["fig14a.csv", "fig14b.csv"], ["one-point cells", "2x2 cells"]),
        ("fig15", ["fig15a.csv", "fig15b.csv", "fig15c.csv", "fig15d.csv"],
         ["quadrilateral centres", "triangle centres", "star", "hexagonal"]),
    ):
        fig, axes = plt.subplots(1, len(files), figsize=(4.5 * len(files), 4), squeeze=False)
        for ax, f, t in zip(axes[0], files, titles):
            panel(ax, read(os.path.join(d, f)),
                  lambda r: (float(r["theta"]), int(r["branch"])),
                  f"{name}: anti-plane, cubic MLS D = 2, {t}",
                  lambda tb: rf"$\theta$ = {tb[0]:g}" + (f", branch {tb[1]}" if tb[1] else ""))
        fig.tight_layout()
        fig.savefig(os.path.join(d, name + ".png"), dpi=110)
        plt.close(fig)

    # Figs 17-18: maximum eigenvalue against the dilation, exact and bounds
    for name in ("fig17", "fig18"):
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for ax, kern in zip(axes, ("cubic", "quartic")):
            rows = read(os.path.join(d, f"{name}_{kern}.csv"))
            for n in sorted({r["nodes"] for r in rows}, key=int):
                rr = [r for r in rows if r["nodes"] == n]
                D = [float(r["dilation"]) for r in rr]
                ax.plot(D, [float(r["lambda_max_dx2"]) for r in rr], "o-", ms=3,
                        label=f"lambda_max, {n} nodes")
                ax.plot(D, [float(r["bound_dx2"]) for r in rr], "s--", ms=3,
                        label=f"element bound, {n} nodes")
            ax.plot(D, [float(r["alpha_dx2"]) for r in rr], "k:", label="closed form alpha/D^2")
            ax.set_yscale("log")
            ax.set_xlabel("dilation D")
            ax.set_ylabel(r"$\lambda\,\Delta x^2 / c^2$")
            ax.set_title(f"{name}: {kern} MLS, gauss2, lumped mass", fontsize=9)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(d, name + ".png"), dpi=110)
        plt.close(fig)

    # work-precision of the reference solver (analysis/bench/workprec.sh), if measured
    files = [os.path.join(d, f) for f in ("workprec_pulse.csv", "workprec_tsph.csv")]
    if all(os.path.exists(f) for f in files):
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for ax, f, title in zip(axes, files, ("displacement form, leapfrog", "stress-velocity form")):
            rows = read(f)
            for m in dict.fromkeys(r["method"] for r in rows):
                rr = [r for r in rows if r["method"] == m]
                ax.loglog([float(r["seconds"]) for r in rr], [float(r["error"]) for r in rr], "o-", ms=3,
                          label=m)
            ax.set_xlabel("run time (s)")
            ax.set_ylabel("relative L2 velocity error at 2L/c")
            ax.set_title(f"Gaussian pulse, {title}", fontsize=9)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "workprec.png"), dpi=110)
        plt.close(fig)

    # time-domain runs of the shipped scenes (analysis/figures.sh), if present
    names = ("run_rod_tensile_lagrangian.csv", "run_rod_tensile_eulerian_sph.csv")
    if all(os.path.exists(os.path.join(d, f)) for f in names):
        fig, ax = plt.subplots(figsize=(6, 4))
        for f, label in zip(names, ("Lagrangian kernel, MLS", "Eulerian kernel, SPH")):
            rows = read(os.path.join(d, f))
            ax.plot([1e6 * float(r["t"]) for r in rows], [float(r["v_center"]) for r in rows], label=label)
        ax.set_xlabel("t (us)")
        ax.set_ylabel("centre velocity (m/s)")
        ax.set_title("Paper 003 Fig. 6: rod under tension, nodal integration", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "run_rod_tensile.png"), dpi=110)
        plt.close(fig)
    names = ("run_tsph_elastic_paper.csv", "run_tsph_elastic_scene.csv")
    if all(os.path.exists(os.path.join(d, f)) for f in names):
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for f, label in zip(names, ("paper's TSPH (eq. 30, alpha = 0)", "scene: linear eq. 30, artificial viscosity 0.03")):
            rows = read(os.path.join(d, f))
            t = [1e3 * float(r["t"]) for r in rows]
            axes[0].plot(t, [-float(r["sigma_end"]) / 1e5 for r in rows], label=label)
            axes[1].plot(t, [float(r["v_mid"]) for r in rows], label=label)
        axes[0].axhline(8.0, color="k", lw=0.6, ls=":")
        axes[0].set_ylabel("compression at the fixed end (1e5 Pa)")
        axes[1].set_ylabel("velocity at x = 0.5 m (m/s)")
        for ax in axes:
            ax.set_xlabel("t (ms)")
            ax.legend(fontsize=7)
        fig.suptitle("Paper 001 Fig. 4: elastic bar, 50 real particles, dt = 9.9e-5 s", fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "run_tsph_elastic.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main()
