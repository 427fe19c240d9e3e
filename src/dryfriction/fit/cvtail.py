"""The trap model's series on a spring, with the steady tail of each segment not simulated
(ours): :func:`spring_series`.

A velocity step of a laboratory record is held for many times its transient (a basalt step:
113 ``a0`` of load-point travel, a transient of about 20), and the ensemble costs
the same per ``a0`` in steady sliding as in the transient. Once the slider has reached steady
sliding at the segment's load velocity ``u`` (a quasi-static spring, no inertia), its state is
unique: the steady population of eq. 29 at ``u`` (spring force = friction, slider velocity =
``u``), so that the rest of the segment is the steady level and nothing needs simulating:

* the segment is run in chunks of :data:`CHUNK_SLIP` ``a0``
  (:func:`dryfriction.ensemble.driving.continue_spring`, which continues one population);
* after each chunk, the mean friction over the last :data:`BLOCK_SLIP` ``a0`` is compared with
  the block before; the segment is steady when, at least :data:`MIN_SLIP` ``a0`` after its
  start, two successive differences are within :data:`STEADY_TOL` (relative to the level)
  *and* a linear drift at the last difference's rate, carried over what is left of the
  segment (at most :data:`DRIFT_BLOCKS` blocks: a transient decays, it does not drift), stays
  within it too;
* the rest of the segment is then the last block's mean (the regular track's sawtooth,
  a granular error of about ``1/traps_per_a0`` of the level, is averaged out there; the
  simulated part keeps it), and a following segment starts from the steady population at
  ``u`` (:class:`dryfriction.ensemble.population.Initial`), placed where the slider ends, with
  the spring pulling with the level.

A segment that does not settle is simulated whole: a series that never settles is
:func:`dryfriction.ensemble.driving.simulate`'s, up to the chunks' sampling grid. Programs with
a hold (``u = 0``, sampled in time) are not taken here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..ensemble.driving import Output, SpringDrive, continue_spring
from ..ensemble.population import Ensemble, Initial, Track, TrapModel
from ..program import Segment
from ..theory.direct import strength_ratio
from ..validation import Array

__all__ = ["spring_series", "steady_level", "CHUNK_SLIP", "BLOCK_SLIP", "MIN_SLIP", "STEADY_TOL",
           "DRIFT_BLOCKS"]

CHUNK_SLIP = 2.0
"""Load-point travel simulated between two tests of steadiness, ``a0``."""
BLOCK_SLIP = 2.0
"""Slip over which the friction is averaged for the test, ``a0`` (200 sawtooth periods of a
100-traps-per-``a0`` track)."""
MIN_SLIP = 6.0
"""Least load-point travel into a segment before it may be called steady, ``a0`` (a trap born
at the change has then left contact: its reach is ``(1 + y_c) a_r``, 2 to 3 ``a0``)."""
STEADY_TOL = 2e-5
"""Relative change of the block mean allowed, and of its extrapolated drift (ours: 1e-5 of a
friction of 0.6, a tenth of the 100-trap track's granular error, a fiftieth of a lab record's
noise)."""
DRIFT_BLOCKS = 10.0
"""Most blocks over which the last block-to-block change is carried as a drift for the test."""


def steady_level(x_pull: Array, mu: Array, start: float, left: float) -> float | None:
    """The level of a segment that has settled (module docstring), else ``None``.

    Parameters
    ----------
    x_pull, mu : ndarray
        The segment's samples so far: load-point position (``a0``, increasing) and friction.
    start : float
        The load-point position where the segment began, ``a0``.
    left : float
        Load-point travel still to go in the segment, ``a0``.
    """
    travel = x_pull[-1] - start
    if travel < max(MIN_SLIP, 3.0 * BLOCK_SLIP):
        return None
    edges = x_pull[-1] - BLOCK_SLIP * np.arange(4)[::-1]  # three blocks, oldest first
    means = [float(np.mean(mu[(x_pull > lo) & (x_pull <= hi)]))
             for lo, hi in zip(edges[:-1], edges[1:], strict=True)]
    level = means[-1]
    tol = STEADY_TOL * abs(level)
    d1, d2 = abs(means[1] - means[0]), abs(means[2] - means[1])
    drift = d2 * min(left / BLOCK_SLIP, DRIFT_BLOCKS)
    return level if max(d1, d2, drift) <= tol else None


def spring_series(model: TrapModel, track: Track, program: Sequence[Segment], stiffness: float,
                  every_slip: float) -> tuple[Array, Array]:
    """The friction of a quasi-static spring slider along ``program``, starting in steady
    sliding at its first velocity, with the steady tail of each segment not simulated
    (module docstring).

    Parameters
    ----------
    model, track : TrapModel, Track
        The traps (with the direct effect where ``model.direct > 0``) and their track.
    program : sequence of Segment
        Load-point velocities (``a0/t0``, every one ``> 0``) and durations (``t0``).
    stiffness : float
        Spring stiffness ``K``, ``F_el/a0``.
    every_slip : float
        Sampling in load-point slip, ``a0``.

    Returns
    -------
    t, mu : ndarray
        Times (``t0``, from 0, increasing) and the friction ``mu_el F/F_el`` there (the spring
        force, which is what a load cell measures), to be read by linear interpolation: a
        steady tail is its two ends at the level.
    """
    segs = [Segment(float(s.velocity), float(s.duration)) for s in program]  # type: ignore
    if not all(s.velocity > 0.0 for s in segs):
        raise ValueError("spring_series takes sliding segments only (velocity > 0)")
    total = float(sum(s.duration for s in segs))
    u0 = segs[0].velocity

    def fresh(u: float, x0: float) -> tuple[Ensemble, float]:
        ens = Ensemble(model, track, Initial("steady", velocity=u), x0=x0,
                       age_horizon=min(max(total, 1.0), 1e12))
        g = strength_ratio(u, model.direct, model.v_ref) if model.direct else 1.0
        return ens, g * ens.observe().force

    ens, force = fresh(u0, 0.0)
    ts, mus = [np.zeros(1)], [np.array([model.mu_el * force])]
    t_now = 0.0
    for k, seg in enumerate(segs):
        u, dur = seg.velocity, seg.duration
        every = Output(every_slip=every_slip)
        chunk_t = CHUNK_SLIP / u
        seg_t, seg_xp, seg_mu = [], [], []
        done, xp_start = 0.0, ens.x + force / stiffness
        while done < dur * (1.0 - 1e-12):
            piece = min(chunk_t, dur - done)
            if dur - done - piece < 0.25 * chunk_t:  # no sliver of a chunk at the end
                piece = dur - done
            res = continue_spring(ens, SpringDrive(stiffness, 0.0, [Segment(u, piece)]),
                                  every, spring_force=force)
            force = stiffness * float(res.x_pull[-1] - res.x[-1])
            seg_t.append(t_now + done + (res.t[1:] - res.t[0]))
            seg_xp.append(res.x_pull[1:])
            seg_mu.append(res.mu[1:])
            done += piece
            if done < dur * (1.0 - 1e-12):
                level = steady_level(np.concatenate(seg_xp),
                                np.concatenate(seg_mu), xp_start, u * (dur - done))
                if level is not None:
                    last = float(seg_t[-1][-1])
                    seg_t.append(np.array([math.nextafter(last, math.inf), t_now + dur]))
                    seg_mu.append(np.full(2, level))
                    seg_xp.append(np.full(2, math.nan))
                    if k + 1 < len(segs):  # the next segment starts from the steady state
                        ens, _ = fresh(u, float(res.x[-1]) + u * (dur - done))
                        force = level / model.mu_el
                    break
        ts.extend(seg_t)
        mus.extend(seg_mu)
        t_now += dur
    return np.concatenate(ts), np.concatenate(mus)
