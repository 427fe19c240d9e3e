"""The (K, V) phase diagram of a slider with mass on the trap model with parameters meant for
paper on paper, the nature of the Hopf bifurcation along K_c(V), and its rate-and-state twin
(docs/hopf.md says where each number comes from).

Usage: python examples/trap_hopf_phase.py OUT_DIR [N_VELOCITIES] [MASS_FACTOR]
writes OUT_DIR/trap_phase.csv and OUT_DIR/trap_phase.png (refuses an OUT_DIR holding them).
MASS_FACTOR multiplies the slider's mass per unit load 1/g (default 1: carried by its own
weight).
"""

import csv
import math
import os
import sys

import numpy as np

from dryfriction.analysis.rsf_hopf import rsf_hopf
from dryfriction.analysis.trap_hopf import trap_hopf
from dryfriction.rsf.law import RateState
from dryfriction.theory.linear_stability import effective_rsf
from dryfriction.theory.model import TrapModel
from dryfriction.theory.static import static_friction

G = 9.81  # m/s^2
D0 = 1e-6  # m, memory length of paper on paper (the value quoted for Heslot et al. 1994)
SLOPE = 8e-3  # d mu_s / d ln t_w (quoted range: "a few 1e-3 to 1e-2")
V_SAT = 30e-6  # m/s, saturation velocity (quoted: "a few tens of um/s"), taken as a0/t0
MU_EL = 0.4  # F_el/N (ours: paper on paper friction ~0.4, the package's synthetic paper)
A = 0.02  # direct-effect coefficient (ours: the value of the earlier continuation)
ALPHA = 0.13  # the paper's trap stiffness


def parameters(mass_factor: float = 1.0) -> dict:
    """Reduced parameters from the SI ones above (ours: docs/hopf.md)."""
    T = np.array([1e2, 1e4])
    per_eps = float(np.diff(static_friction(TrapModel(alpha=ALPHA, eps=0.01), T))[0]
                    / np.log(100.0)) / 0.01
    eps = SLOPE / (MU_EL * per_eps)
    model = TrapModel(alpha=ALPHA, eps=eps, direct=A)
    dc = effective_rsf(0.1, model)["dc"]  # a0, nearly constant below u ~ 1
    a0 = D0 / dc
    t0 = a0 / V_SAT
    # M X'' per unit normal load: m/N = mass_factor/g; reduced M = m a0 / (F_el t0^2)
    mass = mass_factor * a0 / (MU_EL * G * t0**2)
    return {"model": model, "eps": eps, "a0": a0, "t0": t0, "mass": mass, "dc": dc}


def scan(n_v: int = 25, mass_factor: float = 1.0) -> tuple[dict, list[dict]]:
    p = parameters(mass_factor)
    model, mass = p["model"], p["mass"]
    rows = []
    for V in np.geomspace(0.1e-6, 30e-6, n_v):
        u = V * p["t0"] / p["a0"]
        h = trap_hopf(u, model, mass, n=16, panels=12, stretch=1.5)
        tw = effective_rsf(u, model)
        twin = RateState(a=tw["a"], b=tw["b"], dc=tw["dc"], mu0=1.0, v0=u)
        r = rsf_hopf(twin, u, 0.0, mass)
        to_si = MU_EL / p["a0"]  # F_el/a0 per unit normal load -> 1/m
        rows.append({
            "velocity_um_s": V * 1e6, "u": u,
            "k_c_per_load_1_m": h.K_c * to_si, "K_c": h.K_c,
            "frequency_rad_s": h.omega / p["t0"],
            "inertia_ratio": mass * h.omega**2 / h.K_c if math.isfinite(h.K_c) else math.nan,
            "l1_x": h.l1_x, "relative_l1": h.relative_l1, "nature": h.nature,
            "twin_K_c": r.k_c, "twin_l1": r.l1, "twin_nature": r.nature,
        })
        print(" ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                       for k, v in rows[-1].items()), flush=True)
    return p, rows


def crossovers(p: dict, rows: list[dict], key: str = "l1_x") -> list[float]:
    """Velocities (um/s) where the trap model's l1 changes sign between scan points, by
    bisection in ln V (relative 1e-3)."""
    from scipy.optimize import brentq

    def l1(lnv: float) -> float:
        u = math.exp(lnv) * p["t0"] / p["a0"]
        return trap_hopf(u, p["model"], p["mass"], n=16, panels=12, stretch=1.5).l1_x

    out = []
    for r0, r1 in zip(rows, rows[1:], strict=False):
        if r0[key] * r1[key] < 0:
            lnv = brentq(l1, math.log(r0["velocity_um_s"] * 1e-6),
                         math.log(r1["velocity_um_s"] * 1e-6), xtol=1e-3)
            out.append(math.exp(lnv) * 1e6)
    return out


def figure(rows: list[dict], path: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    V = np.array([r["velocity_um_s"] for r in rows])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    colour = {"subcritical": "tab:red", "supercritical": "tab:blue", "degenerate": "k"}
    k = np.array([r["k_c_per_load_1_m"] for r in rows])
    kt = np.array([r["twin_K_c"] for r in rows]) * np.nanmax(k / np.array(
        [r["K_c"] for r in rows]))  # the same F_el/a0 -> 1/m factor
    for nat, c in colour.items():
        sel = np.array([r["nature"] == nat for r in rows])
        if sel.any():
            ax1.plot(V[sel], k[sel], "o", color=c, label=f"trap model: {nat}")
        sel = np.array([r["twin_nature"] == nat for r in rows])
        if sel.any():
            ax1.plot(V[sel], kt[sel], "x", color=c, label=f"ageing-law twin: {nat}")
    none = np.array([r["nature"] == "none" for r in rows])
    if none.any():
        ax1.axvspan(V[none].min(), V[none].max(), color="0.9",
                    label="stable at every K (trap model)")
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_ylabel("k_c / N (1/m)")
    ax1.legend(fontsize=7)
    ax1.set_title(title, fontsize=7, wrap=True)
    l1 = np.array([r["l1_x"] for r in rows])
    ax2.plot(V, l1, "o-", color="k", label="trap model l1 (1/a0^2)")
    ax2.set_yscale("symlog", linthresh=1e-3)
    ax2.axhline(0.0, color="0.5", lw=0.5)
    ax2.set_xlabel("pulling velocity V (um/s)")
    ax2.set_ylabel("l1 (> 0 subcritical)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    out = sys.argv[1]
    n_v = int(sys.argv[2]) if len(sys.argv) > 2 else 25
    factor = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    csv_path, png_path = os.path.join(out, "trap_phase.csv"), os.path.join(out, "trap_phase.png")
    if os.path.exists(csv_path) or os.path.exists(png_path):
        sys.exit(f"OUT_DIR = {out} already holds trap_phase.csv/png: give an empty folder")
    os.makedirs(out, exist_ok=True)
    p, rows = scan(n_v, factor)
    cross = crossovers(p, rows)
    head = (f"# trap model eps={p['eps']:.4g} alpha={ALPHA} A={A} v_ref=1; a0={p['a0']:.3g} m, "
            f"t0={p['t0']:.3g} s, reduced mass {p['mass']:.3g} (m/N = {factor:g}/g), "
            f"mu_el={MU_EL}; l1 changes sign at V = "
            + (", ".join(f"{v:.3g}" for v in cross) or "nowhere") + " um/s")
    tmp = csv_path + ".part"
    with open(tmp, "w", newline="") as fh:
        fh.write(head + "\n")
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, csv_path)
    figure(rows, png_path, head.lstrip("# "))
    print(head)
