"""Precursors and slow fronts of a side-loaded interface: the comparison of
docs/explanation/interface.md with Rubinstein, Cohen & Fineberg (PRL 98, 226103, 2007).

Runs ``examples/interface_side_loaded.toml`` (the contacts aged by a hold of 1000 t0 before the
edge is pushed) and two variants: a short hold (10 t0) and no ageing (``eps = 0``). For each
it prints the events, the precursors from the loaded edge (every arrested event, and those
triggered by the loading: :func:`dryfriction.analysis.catalogue.precursors` with
``triggered=True``), the rank correlation of their lengths with the load ratio, the ratio at
the first system-spanning slip, and the fronts slow or fast against 0.1 x the chain's sound
speed; then draws the precursor curves and the front speeds into one figure. About 5 minutes
of one core::

    python examples/interface_precursors.py [--out interface_precursors.png] [--quick]

``--quick`` runs the aged case only. Reduced units: lengths along the interface in elements,
the load ratio ``F_edge / (N F_el)`` [1], speeds over the sound speed ``sqrt(k_c/m)`` [1].
"""

from __future__ import annotations

import argparse
import copy
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from dryfriction.analysis.catalogue import (  # noqa: E402
    front_regimes,
    precursor_trend,
    precursors,
)
from dryfriction.analysis.fronts import (  # noqa: E402
    default_threshold,
    detect_events,
    from_result,
    interface_normal_load,
    interface_sound_speed,
)
from dryfriction.io.protocol import protocol_from_dict  # noqa: E402

HERE = Path(__file__).resolve().parent


def cases(doc: dict) -> dict[str, dict]:
    """The file's protocol (aged) and its two variants."""
    short = copy.deepcopy(doc)
    short["drive"]["segments"][0]["duration"] = 10.0
    fresh = copy.deepcopy(doc)
    fresh["model"]["eps"] = 0.0
    return {"hold 1000 t0, eps = 0.04": doc, "hold 10 t0, eps = 0.04": short,
            "hold 1000 t0, eps = 0": fresh}


def measure(doc: dict) -> dict:
    """Run one protocol and measure its precursors and fronts."""
    r = protocol_from_dict(doc, "interface").run()
    st = from_result(r)
    events = detect_events(st, default_threshold(r))
    hold = float(doc["drive"]["segments"][0]["duration"])
    normal = interface_normal_load(r)
    every = precursors(events, st, normal, edge="left", edge_gap=1, after=hold)
    trig = precursors(events, st, normal, edge="left", edge_gap=1, after=hold, triggered=True)
    return {"events": events, "every": every, "trig": trig,
            "trend_every": precursor_trend(every), "trend_trig": precursor_trend(trig),
            "fronts": front_regimes(events, interface_sound_speed(r)), "wall": r.info["wall_s"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="interface_precursors.png")
    ap.add_argument("--quick", action="store_true", help="the aged case only")
    args = ap.parse_args()
    doc = tomllib.loads((HERE / "interface_side_loaded.toml").read_text())
    runs = cases(doc)
    if args.quick:
        runs = dict(list(runs.items())[:1])
    res = {}
    for name, d in runs.items():
        m = res[name] = measure(d)
        te, tt, fr = m["trend_every"], m["trend_trig"], m["fronts"]
        span = m["every"].spanning_ratio
        print(f"{name}: {len(m['events'])} events, {span.size} system-spanning"
              f" (first at load ratio {span[0]:.3f})" if span.size else
              f"{name}: {len(m['events'])} events, no system-spanning slip")
        print(f"  every arrested precursor: n = {te.n}, rho = {te.rho:.2f}, p = {te.p_value:.3g}"
              f" ({te.grows}); lengths [element] {m['every'].length.astype(int).tolist()}")
        print(f"  triggered by the loading: n = {tt.n}, rho = {tt.rho:.2f}, p = {tt.p_value:.3g}"
              f" ({tt.grows}); lengths [element] {m['trig'].length.astype(int).tolist()}"
              f" at load ratios [1] {np.round(m['trig'].ratio, 3).tolist()}")
        print(f"  fronts: {fr.count('slow')} slow, {fr.count('fast')} fast, "
              f"{fr.count('undetermined')} undetermined (against {fr.fraction:g} x sound speed);"
              f" speed / sound speed from {np.min(fr.ratio, initial=np.inf):.2f}"
              f" to {np.max(fr.ratio, initial=-np.inf):.2f}; run {m['wall']:.0f} s")

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    for k, (name, m) in enumerate(res.items()):
        e, t = m["every"], m["trig"]
        left.plot(e.ratio, e.length, "o", mfc="none", color=f"C{k}", alpha=0.6)
        left.plot(t.ratio, t.length, "o-", color=f"C{k}",
                  label=f"{name}: rho = {m['trend_trig'].rho:.2f}, p = "
                        f"{m['trend_trig'].p_value:.2g}")
        for s in e.spanning_ratio:
            left.axvline(s, color=f"C{k}", ls=":", lw=1)
        fr = m["fronts"]
        right.plot(np.full(fr.ratio.size, k) + np.linspace(-0.2, 0.2, fr.ratio.size),
                   fr.ratio, "o", color=f"C{k}")
    left.set_xlabel("load ratio at arrest  F_edge / (N F_el)  [1]")
    left.set_ylabel("precursor length  [element]")
    left.set_title("open: every arrested event; filled: triggered by the loading; "
                   "dotted: system-spanning", fontsize="small")
    left.legend(fontsize="x-small")
    right.axhline(0.1, color="k", ls="--", lw=1, label="0.1 x sound speed (slow below)")
    right.set_yscale("log")
    right.set_xticks(range(len(res)), list(res), fontsize="x-small")
    right.set_ylabel("front speed / sound speed sqrt(k_c/m)  [1]")
    right.legend(fontsize="small")
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
