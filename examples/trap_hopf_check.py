"""The trap model's l1 against simulations (docs/hopf.md; dryfriction.analysis.trap_hopf_check).

Usage: python examples/trap_hopf_check.py reduced|population|ensemble|cycle OUT.json [CASES] [TRAPS]
  reduced : the Chebyshev reduction integrated by Radau (cheap; minutes)
  population: the same continuous population by population_check: settled cycles from two
            starts, the unstable cycle bisected (8 halvings), exponents; POPULATION below
            (5-15 CPU-minutes a case)
  ensemble: the package's trap ensemble started from a steady population of (1 + kick) u
            (continue_spring, 100 traps/a0; tens of minutes)
  cycle   : the package's trap ensemble released from the linear cycle (cycle_amplitudes),
            TRAPS pairs per a0 (default 100); CYCLE below
CASES: comma-separated names from the simulator's table (default: all of it).

eps = 0.04, alpha = 0.13, A = 0.02, v_ref = 1 (the values of docs/hopf.md). Supercritical
cases run below K_c at K = K_c (1 - d) until settled (amplitude change < 1e-3 over 50
periods); subcritical ones bisect the start above K_c, K = K_c (1 + d), between a decaying and
a growing run. Amplitudes: half peak-to-peak spring force, F_el.
"""

import json
import math
import sys
import time

import numpy as np

from dryfriction.analysis.trap_hopf import TrapField, trap_hopf
from dryfriction.analysis.trap_hopf_check import (
    amplitude_exponent,
    cycle_amplitudes,
    ensemble_amplitudes,
    population_check,
    reduced_amplitudes,
    settled,
    threshold,
)
from dryfriction.theory.model import TrapModel

MODEL = TrapModel(eps=0.04, alpha=0.13, direct=0.02)
# name: (u, mass, distances); the sign of l1 (from trap_hopf) picks the check
CASES = {
    "qs_u1": (1.0, 0.0, (0.01, 0.02, 0.04)),
    "qs_u0.01": (0.01, 0.0, (0.005, 0.01)),
    "inertial_u1": (1.0, 0.845, (0.01, 0.02)),
    "mass_u0.01": (0.01, 110.0, (0.01, 0.02)),
}
RES = {"n": 12, "panels": 10, "stretch": 2.0}  # l1 settled to 1e-6 there (docs/hopf.md)
ENSEMBLE = {"qs_u1": (1.0, 0.0, (0.02, 0.01)), "qs_u0.01": (0.01, 0.0, (0.02, 0.04)),
            "inertial_u1": (1.0, 0.845, (0.02, 0.01, 0.05, 0.1))}


# name: (u, mass, distances): ``cycle``; distances where the cycle keeps the slider moving
# forward (slip omega_c/u < 0.9 at the normal form's amplitude)
CYCLE = {
    "qs_u1": (1.0, 0.0, (0.02, 0.03, 0.05)),
    "qs_u0.3": (0.3, 0.0, (0.01, 0.015, 0.02)),
    "mass_u1": (1.0, 0.03, (0.02, 0.05, 0.08)),
    "mass_u0.3": (0.3, 0.3, (0.02, 0.05, 0.08)),
    "qs_u0.01": (0.01, 0.0, (0.005, 0.01)),
    "qs_u0.03": (0.03, 0.0, (0.005, 0.01)),
}


# name: (u, mass, distances): ``population``
POPULATION = {
    "qs_u1": (1.0, 0.0, (0.005, 0.01, 0.02)),
    "qs_u0.01": (0.01, 0.0, (0.0025, 0.005, 0.01)),
    "qs_u0.03": (0.03, 0.0, (0.0025, 0.005, 0.01)),
    "mass_u0.3": (0.3, 0.3, (0.01, 0.02, 0.04)),
}


def population_case(u: float, mass: float, ds: tuple[float, ...]) -> dict:
    t = time.process_time()
    out = population_check(u, MODEL, ds, mass=mass)
    out["cpu_s"] = time.process_time() - t
    print(json.dumps(out, default=float), flush=True)
    return out


def _case(hop, u: float, mass: float) -> dict:  # type: ignore[no-untyped-def]
    """The Hopf point's numbers, before the simulated rows."""
    return {"u": u, "mass": mass, "K_c": hop.K_c, "omega": hop.omega, "l1_x": hop.l1_x,
            "nature": hop.nature, "rows": []}


def reduced_case(u: float, mass: float, ds: tuple[float, ...]) -> dict:
    hop = trap_hopf(u, MODEL, mass, **RES)
    fld = TrapField(u, MODEL, mass, 0.0, **RES)
    out = _case(hop, u, mass)
    for d in ds:
        t = time.process_time()
        if hop.l1_x < 0:
            K = hop.K_c * (1 - d)
            pred = hop.force_amplitude(K)
            r = settled(lambda s, p, K=K: reduced_amplitudes(fld, hop, K, s, p), pred, 100,
                        max_periods=400)
        else:
            K = hop.K_c * (1 + d)
            pred = hop.force_amplitude(K)
            beta = abs(hop.dbeta_dK * (K - hop.K_c))
            periods = int(max(20, min(50, 2.0 / (beta * 2 * math.pi / hop.omega))))

            def grows(s: float, K: float = K, periods: int = periods
                      ) -> tuple[bool, np.ndarray]:
                try:
                    a = reduced_amplitudes(fld, hop, K, s, periods)
                except (RuntimeError, ValueError):  # the solver failed on a runaway
                    return True, np.array([s])
                return bool(a[-1] > a[1]), a

            r = threshold(grows, 0.8 * pred, 1.25 * pred, steps=1)
        r.update({"d": d, "K": K, "predicted": pred, "cpu_s": time.process_time() - t})
        out["rows"].append(r)
        print(json.dumps(r), flush=True)
    if hop.l1_x < 0 and len(ds) >= 3:
        out["exponent"] = amplitude_exponent([r["d"] for r in out["rows"]],
                                             [r["amplitude"] for r in out["rows"]])
    return out


def ensemble_case(u: float, mass: float, ds: tuple[float, ...]) -> dict:
    hop = trap_hopf(u, MODEL, mass, **RES)
    out = _case(hop, u, mass)
    for d in ds:
        t = time.process_time()
        if hop.l1_x < 0:
            K = hop.K_c * (1 - d)
            r = settled(lambda s, p, K=K: ensemble_amplitudes(u, MODEL, hop, K, s, p, mass=mass),
                        0.1 if mass > 0 else 0.05, 800 if mass > 0 else 150,
                        max_periods=1600 if mass > 0 else 300)
        else:
            K = hop.K_c * (1 + d)

            def grows(s: float, K: float = K) -> tuple[bool, np.ndarray]:
                a = ensemble_amplitudes(u, MODEL, hop, K, s, 40, mass=mass)
                return bool(np.mean(a[-3:]) > np.mean(a[2:5])), a

            r = threshold(grows, 0.01, 0.3, steps=6)
        r.update({"d": d, "K": K, "predicted": hop.force_amplitude(K),
                  "cpu_s": time.process_time() - t})
        out["rows"].append(r)
        print(json.dumps(r), flush=True)
    return out


def cycle_case(u: float, mass: float, ds: tuple[float, ...], traps: float = 100.0) -> dict:
    """The ensemble released from the linear cycle: settled cycles below ``K_c``
    (supercritical), or the unstable cycle bracketed above it (subcritical)."""
    hop = trap_hopf(u, MODEL, mass, **RES)
    out = {**_case(hop, u, mass), "traps_per_a0": traps}
    top = 0.9 * u / hop.omega  # the largest linear cycle that keeps the slider moving forward
    for d in ds:
        t = time.process_time()
        if hop.l1_x < 0:
            K = hop.K_c * (1 - d)
            slip = min(hop.slip_amplitude(K), top)
            r = settled(lambda s, p, K=K: cycle_amplitudes(u, MODEL, hop, K, s / K, p, traps,
                                                           mass), K * slip, 60, max_periods=240)
        else:
            K = hop.K_c * (1 + d)
            pred = hop.force_amplitude(K)
            beta = abs(hop.dbeta_dK * (K - hop.K_c))
            periods = int(max(30, min(80, 2.0 / (beta * 2 * math.pi / hop.omega))))

            def grows(s: float, K: float = K, periods: int = periods
                      ) -> tuple[bool, np.ndarray]:
                a = cycle_amplitudes(u, MODEL, hop, K, s / K, periods, traps, mass)
                print(json.dumps({"start": s, "first": a[1], "last": a[-1]}), flush=True)
                return bool(np.mean(a[-3:]) > np.mean(a[1:4])), a

            r = threshold(grows, 0.5 * pred, min(1.5 * pred, K * top), steps=3)
        r.update({"d": d, "K": K, "predicted": hop.force_amplitude(K),
                  "cpu_s": time.process_time() - t})
        out["rows"].append(r)
        print(json.dumps(r), flush=True)
    return out


if __name__ == "__main__":
    which, path = sys.argv[1], sys.argv[2]
    table = {"reduced": CASES, "population": POPULATION, "ensemble": ENSEMBLE,
             "cycle": CYCLE}[which]
    names = sys.argv[3].split(",") if len(sys.argv) > 3 else list(table)
    run = {"reduced": reduced_case, "population": population_case, "ensemble": ensemble_case,
           "cycle": cycle_case}[which]
    traps = float(sys.argv[4]) if len(sys.argv) > 4 else 100.0
    result = {}
    for name in names:
        result[name] = run(*table[name], traps) if which == "cycle" else run(*table[name])
        with open(path, "w") as fh:
            json.dump(result, fh, indent=1)
