"""Where the zoo's change times are missed, and whether the records hold the information to
place them (issue 23).

For each zoo record (``tests/records_zoo.py``; default the held-out records 150-449) the
detector is run as ``bench_detect`` runs it (written in its dialect, read back), and each true
change of a record whose number of changes is right gets: its artifact class (the
generator's labels: the velocity ratio, the servo error ``red``, the machine oscillation
``wobble``, the ``velocity`` dialect), the detector's time error over its tolerance
(the larger of one sample and 0.5 s), whether the detector marks it not placed, and two
**information bounds** under the zoo's own noise model with its parameters known: the
Cramér-Rao standard deviation of the change time (Fisher information of the hinge, ours
below) and the posterior of an oracle that knows the model (below).

The bound (ours, from the generator's model; the hinge's Fisher information as in Feder,
*Ann. Statist.* 3, 49-83, 1975, for continuous two-phase regression, where the change time is
a regular parameter): the displacement is ``x_i = c + v_1 (t_i - t_0) + sum_j (v_(j+1) - v_j)
(t_i - t_j)+ + n_i`` with Gaussian noise ``n`` of covariance ``C``; with the velocities and
the offset free and every other change time known, the information on the change time
``t_k`` is ``I_k = (v_(k+1) - v_k)**2 ||P L^-1 h_k||**2``, ``h_k = 1[t_i > t_k]`` (the mean's
derivative, up to its sign), ``L L^T = C``, ``P`` the projection off the whitened nuisance
columns; ``sd_k = I_k**-0.5``. ``L^-1`` is applied by the Kalman filter of the zoo's servo
(``records_zoo.servo_error``: ``eta`` an exact AR(1), ``e_i = rho_i e_(i-1) + V_(i-1)
eta_(i-1) tau_s (1 - rho_i)``; Durbin & Koopman, *Time Series Analysis by State Space
Methods*, ch. 4), observed with the transducer's white noise; in the ``velocity`` dialect the
displacement is the trapezoid integral of the servo's reading, so its noise is the servo
error plus a random walk of the reading's 2 % noise (and its quantum), two more states.

Two Cramér-Rao bounds:

* ``strict``: the machine oscillation, the bursts, the drift and the resets known (no
  information lost to them) and the displacement quantum left out (a quantised record is a
  function of the unquantised one, so it holds less Fisher information): no estimator that is
  unbiased near the truth does better. A lower bound.
* ``profile``: the oscillation's amplitude and phase free (``int V sin``, ``int V cos`` of
  each of its two periods, as ``bench_detect_oracle``'s Kalman oracle), the quantum as white
  noise of variance ``q**2 / 12``.

A Cramér-Rao bound need not be attained: on ``bench_detect_oracle``'s ratio-1.3 records the
maximum-likelihood oracle's errors are several times it (``--check``), so a small bound says
nothing about reaching the tolerance. What does is the **posterior oracle**
(:func:`posterior`): the exact posterior of the change time under the zoo's model (every
row within 60 s, the oscillation, bursts, drift and resets known, flat priors on the offset,
the velocities and the time), whose best probability ``P*`` of lying within the tolerance of
some estimate is the most any estimator can have on that record (Bayes' rule with a 0-1 loss;
the model's servo drive is taken at the true program, a little more than any estimator
knows). Summed over the changes, ``1 - P*`` is the number of changes the best estimator is
expected to miss. A change is *beyond the information* when ``P* < 0.95``.

Printed per class: the changes, the detector's times right, the misses' |error| /
tolerance, the median Cramér-Rao ``1.96 sd`` / tolerance, the oracle's mean ``P*``, the
changes with ``P* < 0.95`` and the expected misses; then the share of the records with a
change beyond the information and the best estimator's expected rate (the 98 % target is
beyond the information where that is below 98 %), the detector's rates and CPU time, and the
confusion table of its "not placed" flag against the times right.

Run: ``python -m benchmarks bench_detect_bound [START:STOP | N] [--csv PATH]`` (default
150:450; ``--csv`` writes one row per change); ``--check`` compares the bounds with
``bench_detect_oracle``'s maximum-likelihood oracle on its records (:func:`check`);
``--ceiling`` prints only the records the best estimator is expected to get wrong, knowing the
artifacts and not knowing the oscillation's amplitude and phase or the bursts
(:func:`ceiling`; about 0.2 s per record, no detection).
"""

from __future__ import annotations

import math
import os
import re
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import numba  # noqa: E402
import numpy as np  # noqa: E402

import records_zoo as z  # noqa: E402
from dryfriction.records.lab import detect_program, read_record  # noqa: E402

READING_NOISE = 0.02
"""Relative white noise of the ``velocity`` dialect's reading (``records_zoo.make_record``)."""


@numba.njit(cache=True)
def _kalman_whiten(dt: np.ndarray, v: np.ndarray, vu: np.ndarray, Y: np.ndarray, s2: float,
                   te: float, ts: float, R: float) -> np.ndarray:
    """Kalman innovations over their standard deviations of every column of ``Y`` (module
    docstring). State ``(eta, e, w, u)``: the servo's disturbance and position error, the
    random walk of an integrated reading and the reading's last noise (variance ``vu`` per
    sample; 0 for a displacement transducer); observed ``e + w`` plus white noise of variance
    ``R``. ``dt`` the sampling intervals, ``v`` the commanded velocity at each sample."""
    n, m = Y.shape
    out = np.empty_like(Y)
    M = np.zeros((4, m))
    P = np.zeros((4, 4))
    c0 = v[0] * ts
    P[0, 0] = s2
    P[0, 1] = c0 * s2
    P[1, 0] = c0 * s2
    P[1, 1] = c0 * c0 * s2
    P[3, 3] = vu[0]
    F = np.zeros((4, 4))
    Pn = np.zeros((4, 4))
    for i in range(n):
        if i > 0:
            h = dt[i - 1]
            a = math.exp(-h / te)
            rho = math.exp(-h / ts)
            c = v[i - 1] * ts * (1.0 - rho)
            F[0, 0] = a
            F[1, 0] = c
            F[1, 1] = rho
            F[2, 2] = 1.0
            F[2, 3] = 0.5 * h
            for j in range(m):
                m0, m1, m2, m3 = M[0, j], M[1, j], M[2, j], M[3, j]
                M[0, j] = a * m0
                M[1, j] = c * m0 + rho * m1
                M[2, j] = m2 + 0.5 * h * m3
                M[3, j] = 0.0
            # P <- F P F^T + Q (F's last row is 0: u is new noise each sample)
            for r in range(4):
                for s in range(4):
                    acc = 0.0
                    for p in range(4):
                        if F[r, p] == 0.0:
                            continue
                        for q in range(4):
                            acc += F[r, p] * P[p, q] * F[s, q]
                    Pn[r, s] = acc
            Pn[0, 0] += s2 * (1.0 - a * a)
            Pn[3, 3] += vu[i]
            Pn[2, 2] += 0.25 * h * h * vu[i]
            Pn[2, 3] += 0.5 * h * vu[i]
            Pn[3, 2] += 0.5 * h * vu[i]
            for r in range(4):
                for s in range(4):
                    P[r, s] = 0.5 * (Pn[r, s] + Pn[s, r])
        ph = np.empty(4)
        for r in range(4):
            ph[r] = P[r, 1] + P[r, 2]
        Fv = ph[1] + ph[2] + R
        sf = math.sqrt(Fv)
        for j in range(m):
            inn = Y[i, j] - M[1, j] - M[2, j]
            out[i, j] = inn / sf
            for r in range(4):
                M[r, j] += ph[r] / Fv * inn
        for r in range(4):
            for s in range(4):
                P[r, s] -= ph[r] * ph[s] / Fv
    return out


def bounds(rec: z.ZooRecord, strict: bool) -> np.ndarray:
    """The Cramér-Rao standard deviation (s) of each change time of ``rec`` (module
    docstring; ``strict`` or ``profile``)."""
    t = rec.t - float(rec.t[0])
    ch = np.asarray(rec.changes, float)
    vel = np.asarray(rec.velocities, float)
    vl = vel[np.searchsorted(ch, t, side="right")]
    red = "red" in rec.artifacts
    velocity = rec.dialect == "velocity"
    if velocity:
        # the reading's 2 % noise and its quantum (the quantum only in the profile bound)
        vu = (READING_NOISE * vl) ** 2 + (0.0 if strict else z.QUANTUM**2 / 12.0)
        R = (1e-12) ** 2  # the file's 9 digits: no white displacement noise
    else:
        vu = np.zeros_like(t)
        R = z.WHITE**2 + (0.0 if strict else rec.quantum**2 / 12.0)
    cols = [np.ones_like(t), t] + [np.maximum(t - c, 0.0) for c in ch]
    if not strict and "wobble" in rec.artifacts:
        for _amp, per in z.WOBBLE:
            # the exact integral over each sample interval (as the zoo's across a gap)
            w = 2.0 * np.pi / per
            for f in (-np.cos(w * t) / w, np.sin(w * t) / w):
                cols.append(np.concatenate([[0.0], np.cumsum(vl[1:] * np.diff(f))]))
    steps = [(t > c).astype(float) for c in ch]
    Y = np.column_stack(cols + steps)
    W = _kalman_whiten(np.diff(t), vl, vu, np.ascontiguousarray(Y),
                       z.SERVO_RMS**2 if red else 0.0, z.SERVO_ETA_TAU, z.SERVO_TAU, R)
    nb = len(cols)
    Q, _ = np.linalg.qr(W[:, :nb])
    Hp = W[:, nb:] - Q @ (Q.T @ W[:, nb:])
    info = np.einsum("ij,ij->j", Hp, Hp) * np.diff(vel) ** 2
    with np.errstate(divide="ignore"):
        return 1.0 / np.sqrt(info)


def posterior(rec: z.ZooRecord, k: int, half: float = 60.0, span: float = 10.0,
              step: float = 0.05, knows: bool = True) -> tuple[float, float]:
    """The true-model oracle's posterior of change ``k``'s time (module docstring): the best
    probability any estimate has of lying within the tolerance, and the posterior's standard
    deviation, s.

    The data within ``half`` s of the change (not past its neighbours, whose times are
    known), the known oscillation, bursts, drift and reset taken out (the hinge's regressor
    is ``E(t) - E(t_c)``, ``E = int (1 + eps)``), whitened by the servo's Kalman filter with
    the quantum as white noise; each candidate time on a grid of ``step`` s within ``span``
    s of the truth weighs ``exp(gain / 2) / ||h_w||`` (flat priors on the offset and the
    velocities integrated out; ``gain`` the generalised sum of squares the hinge saves).

    ``knows=False``: the oracle that knows the servo's model, the drift and the reset but not
    the realisation of the velocity's fluctuations (:func:`ceiling`): ``E(t) = t``, the
    oscillation's two periods (``records_zoo.WOBBLE``) each two free regressors ``int V sin(2
    pi t / P)`` and ``int V cos(2 pi t / P)`` (``V`` the commanded velocity; amplitude and
    phase integrated out with flat priors, as the offset), the bursts left in the data."""
    t = rec.t - float(rec.t[0])
    ch = np.asarray(rec.changes, float)
    vel = np.asarray(rec.velocities, float)
    tc = float(ch[k])
    a = max(tc - half, float(ch[k - 1]) if k > 0 else -np.inf)
    b = min(tc + half, float(ch[k + 1]) if k + 1 < ch.size else np.inf)
    if not knows:
        E = t.copy()
    elif rec.e_int is not None:  # as the zoo integrated it (exact across a gap)
        E = rec.e_int
    else:
        g = 1.0 + (rec.eps if rec.eps is not None else np.zeros_like(t))
        E = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(t))])
    velocity = rec.dialect == "velocity"
    if velocity:
        v = np.asarray(rec.v, float)
        y = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    else:
        y = rec.x - (rec.x_known if rec.x_known is not None else 0.0)
    sel = (t >= a) & (t < b)
    tt, y, E = t[sel], y[sel], E[sel]
    vl = vel[np.searchsorted(ch, tt, side="right")]
    grid = tc + np.arange(-span, span + 1e-9, step)
    grid = grid[(grid > tt[0] + 1.0) & (grid < tt[-1] - 1.0)]
    Eg = np.interp(grid, tt, E)
    if velocity:
        vu = (READING_NOISE * vl) ** 2 + z.QUANTUM**2 / 12.0
        R = (1e-12) ** 2
    else:
        vu = np.zeros_like(tt)
        R = z.WHITE**2 + rec.quantum**2 / 12.0
    nuisance = [np.ones_like(tt), E - E[0]]
    if not knows and "wobble" in rec.artifacts:
        for _amp, per in z.WOBBLE:
            for f in (np.sin, np.cos):
                g = vl * f(2.0 * np.pi * tt / per)
                col = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(tt))])
                nuisance.append(col / max(float(np.abs(col).max()), 1e-300))
    m = len(nuisance)
    cols = np.column_stack([y - y.mean(), *nuisance,
                            np.maximum(E[:, None] - Eg[None, :], 0.0)])
    W = _kalman_whiten(np.diff(tt), vl, vu, np.ascontiguousarray(cols),
                       z.SERVO_RMS**2 if "red" in rec.artifacts else 0.0, z.SERVO_ETA_TAU,
                       z.SERVO_TAU, R)
    Q, _ = np.linalg.qr(W[:, 1:1 + m])
    yp = W[:, 0] - Q @ (Q.T @ W[:, 0])
    Hp = W[:, 1 + m:] - Q @ (Q.T @ W[:, 1 + m:])
    hh = np.einsum("ij,ij->j", Hp, Hp)
    lp = 0.5 * (Hp.T @ yp) ** 2 / hh - 0.5 * np.log(hh)
    w = np.exp(lp - lp.max())
    w /= w.sum()
    tol = z.tolerance(t, tc)
    cw = np.concatenate([[0.0], np.cumsum(w)])
    lo = np.searchsorted(grid, grid - tol, side="left")
    hi = np.searchsorted(grid, grid + tol, side="right")
    best = float(np.clip(np.max(cw[hi] - cw[lo]), 0.0, 1.0))
    mean = float(w @ grid)
    return best, float(np.sqrt(w @ (grid - mean) ** 2))


def klass(rec: z.ZooRecord, ratio: float) -> str:
    """A change's artifact class: its ratio (or a hold), and which of the servo error, the
    machine oscillation and the velocity dialect the record has."""
    tags = [t for t in ("red", "wobble") if t in rec.artifacts]
    if rec.dialect == "velocity":
        tags.append("vel")
    r = "hold" if not np.isfinite(ratio) else f"{ratio:.3g}"
    return f"{r:>4} {'+'.join(tags) or '-'}"


scores: list[tuple[z.Score, int]] = []
"""The last :func:`run`'s scores (``records_zoo.score``) and row counts."""


def run(start: int, stop: int) -> list[dict]:
    """One row per true change of records ``start`` to ``stop - 1`` (module docstring); the
    records whose number of changes is wrong give rows with ``count_right`` False."""
    rows = []
    scores.clear()
    with tempfile.TemporaryDirectory() as tmp:
        # a process's first detection loads the compiled kernel: outside the timed ones
        detect_program(read_record(z.write(z.make_record(0, "up", (), "tab_um"), Path(tmp))))
        for i, prog, arts, dialect in z.specs(stop):
            if i < start:
                continue
            rec = z.make_record(i, prog, arts, dialect)
            path = z.write(rec, Path(tmp))
            lab = read_record(path)
            c0 = time.process_time()
            det = detect_program(lab)
            cpu = time.process_time() - c0
            path.unlink()
            s = z.score(rec, det, cpu)
            scores.append((s, rec.rows))
            sd_s, sd_p = bounds(rec, True), bounds(rec, False)
            t = rec.t - float(rec.t[0])
            segs = [q for p, q in zip(det.segments, det.segments[1:], strict=False)
                    if q.velocity != p.velocity]
            vel = rec.velocities
            for k, c in enumerate(rec.changes):
                v1, v2 = abs(vel[k]), abs(vel[k + 1])
                ratio = max(v1, v2) / min(v1, v2) if min(v1, v2) > 0 else math.inf
                row = {"record": i, "program": prog, "class": klass(rec, ratio),
                       "ratio": ratio, "tol": z.tolerance(t, c), "sd_strict": sd_s[k],
                       "sd_profile": sd_p[k], "count_right": bool(s.changes)}
                # the posterior only where the bound leaves doubt: the maximum-likelihood
                # oracle's rms error was 3.2-4.7 times the Cramer-Rao sd (``--check``), so a
                # tolerance of 30 sd (6 such rms errors) is taken as met
                row["p_best"], row["sd_post"] = ((1.0, float("nan"))
                                                 if 30.0 * sd_p[k] < row["tol"]
                                                 else posterior(rec, k))
                if s.changes:
                    _r, err, _tol, inside, placed = s.changes[k]
                    sg = segs[k]
                    row.update(err=err, placed=placed, inside=inside, z=sg.confidence,
                               half_lo=sg.t_start - sg.start_lo, half_hi=sg.start_hi - sg.t_start,
                               edge=sg.start_edge)
                rows.append(row)
    return rows


def report(rows: list[dict], start: int, stop: int) -> None:
    """Print the per-class table, the share of the zoo beyond the information and the flag's
    confusion table."""
    nrec = stop - start
    print(f"zoo records {start} to {stop - 1}: {nrec} records, {len(rows)} true changes")
    if scores:
        sc = [q for q, _ in scores]
        found = sum(q.found for q in sc)
        right = 100 * np.mean([q.right for q in sc])
        print(f"detector: right number {100 * np.mean([q.count_right for q in sc]):.1f} %, "
              f"and every time within max(1 sample, 0.5 s) {right:.1f} %; false changes "
              f"{100 * sum(q.false for q in sc) / max(found, 1):.2f} %; "
              f"CPU {1e6 * sum(q.cpu for q in sc) / sum(n for _, n in scores):.2f} s per 1e6 "
              "rows")
    print(f"{'class':<20} {'changes':>7} {'det right':>9} {'misses |err|/tol':>22} "
          f"{'CR 1.96sd/tol':>13} {'oracle best':>11} {'P*<0.95':>7} {'exp. misses':>11}")
    for k in sorted({r["class"] for r in rows}):
        g = [r for r in rows if r["class"] == k]
        gc = [r for r in g if r["count_right"]]
        miss = sorted(abs(r["err"]) / r["tol"] for r in gc if abs(r["err"]) > r["tol"])
        hs = np.array([1.96 * r["sd_strict"] / r["tol"] for r in g])
        pb = np.array([r["p_best"] for r in g])
        right = (100 * (1 - len(miss) / len(gc))) if gc else float("nan")
        ms = " ".join(f"{m:.2g}" for m in miss[:5]) + (" ..." if len(miss) > 5 else "")
        print(f"{k:<20} {len(g):>7d} {right:>8.0f}% {ms:>22} {np.median(hs):>13.2g} "
              f"{100 * pb.mean():>10.1f}% {int((pb < 0.95).sum()):>7d} {(1 - pb).sum():>11.2f}")
    for which in ("strict", "profile"):
        recs = {r["record"] for r in rows if 1.96 * r[f"sd_{which}"] > r["tol"]}
        print(f"Cramer-Rao ({which}): {len(recs)} of {nrec} records "
              f"({100 * len(recs) / nrec:.1f} %) have a change whose 95 % half-width exceeds "
              "its tolerance")
    best: dict[int, float] = {}
    for r in rows:
        best[r["record"]] = best.get(r["record"], 1.0) * r["p_best"]
    low = {r["record"] for r in rows if r["p_best"] < 0.95}
    miss = sum(1.0 - p for p in best.values())
    print(f"posterior oracle: {len(low)} of {nrec} records ({100 * len(low) / nrec:.1f} %) have "
          f"a change that no estimate places within its tolerance with 95 % probability; the "
          f"best estimator is expected to miss {miss:.1f} records ({100 * miss / nrec:.1f} %: "
          f"at most {100 * (1 - miss / nrec):.1f} % right; the target needs >= 98 %)")
    cr = [r for r in rows if r["count_right"]]
    wrong = [abs(r["err"]) > r["tol"] for r in cr]
    flag = [not r["placed"] for r in cr]
    tab = [[sum(w and f for w, f in zip(wrong, flag, strict=True)),
            sum(w and not f for w, f in zip(wrong, flag, strict=True))],
           [sum(f and not w for w, f in zip(wrong, flag, strict=True)),
            sum(not w and not f for w, f in zip(wrong, flag, strict=True))]]
    print(f"'not placed' against the times ({len(cr)} changes of the records with the right "
          f"number): wrong & flagged {tab[0][0]}, wrong & unflagged {tab[0][1]}, right & "
          f"flagged {tab[1][0]}, right & unflagged {tab[1][1]}")
    honest = sum(f and not w and r["p_best"] < 0.95
                 for w, f, r in zip(wrong, flag, cr, strict=True))
    print(f"of the {tab[1][0]} right & flagged, {honest} are changes the posterior oracle "
          "itself places within the tolerance with less than 95 % probability")


def ceiling(start: int, stop: int) -> None:
    """The share of zoo records ``start`` to ``stop - 1`` the best estimator is expected to
    get right, by two posterior oracles (:func:`posterior` on every change, a record's
    probability the product of its changes'): the one that knows the realisation of the
    oscillation, the bursts, the drift and the reset, and the one that knows the servo's
    model but must take the oscillation's amplitude and phase from the data and does not know
    the bursts (``knows=False``). Neither counts the number of changes: both are given it. No
    estimator reaches the first; the second is the nearer to what a detector can know (it
    still knows the servo's model and parameters, the periods and the program's speeds)."""
    out: dict[str, list[float]] = {}
    for i, prog, arts, dialect in z.specs(stop):
        if i < start:
            continue
        rec = z.make_record(i, prog, arts, dialect)
        pk = [float(np.prod([posterior(rec, k, knows=kn)[0] for k in range(len(rec.changes))]))
              for kn in (True, False)]
        for key in ("all", prog):
            q = out.setdefault(key, [0.0, 0.0, 0.0])
            q[0] += 1
            q[1] += 1.0 - pk[0]
            q[2] += 1.0 - pk[1]
    print(f"zoo records {start} to {stop - 1}: records the best estimator is expected to get "
          "wrong (its change times, the number given)")
    print(f"{'program':<10} {'records':>7} {'knowing the artifacts':>22} "
          f"{'oscillation free, bursts unknown':>33}")
    for key in ["all"] + sorted(k for k in out if k != "all"):
        n, a, b = out[key]
        print(f"{key:<10} {int(n):>7d} {a:>10.1f} ({100 * (1 - a / n):5.1f} %) "
              f"{b:>21.1f} ({100 * (1 - b / n):5.1f} %)")


def check(n: int = 40) -> None:
    """The bounds against ``bench_detect_oracle``'s maximum-likelihood oracle on its own
    records (servo error only: the records' model is then exactly the bounds'): the oracle's
    rate within the tolerance (the Kalman filter on every row within 60 s), the posterior's
    expected best rate (:func:`posterior`, which should be at least the oracle's, up to the
    sampling of ``n`` records per case) and the oracle's rms error over the Cramér-Rao sd
    (1 for an efficient estimator; above 1 where the bound is not attained)."""
    from benchmarks import bench_detect_oracle as bo

    rng = np.random.default_rng(7)
    for ratio in (1.3, 2.0, 3.0):
        out = []
        for k in range(n):
            s = bo.simulate(rng, ratio, k % 2 == 0, False)
            e = bo.oracle_kalman(s, 60.0)
            rec = z.ZooRecord("check", "up", ("red",), "tab_um", s.t, s.x, s.x, s.x, [s.t0],
                              velocities=[s.v1, s.v2])
            out.append((e, posterior(rec, 0)[0], bounds(rec, False)[0], s.tol))
        a = np.array(out)
        print(f"ratio {ratio}, servo error only, {n} records: the oracle within the tolerance "
              f"{100 * np.mean(a[:, 0] <= a[:, 3]):.0f} %, the posterior's best "
              f"{100 * a[:, 1].mean():.0f} % (expected), rms(oracle error / Cramer-Rao sd) "
              f"{np.sqrt(np.mean((a[:, 0] / a[:, 2]) ** 2)):.2f}")


def main() -> None:
    args = [a for a in sys.argv[1:] if a != "bench_detect_bound"]
    csv = None
    if "--csv" in args:
        csv = args[args.index("--csv") + 1]
        args = [a for a in args if a not in ("--csv", csv)]
    if "--check" in args:
        check()
        return
    start, stop = 150, 450
    for a in args:
        if a.isdigit():
            start, stop = 0, int(a)
        elif re.fullmatch(r"\d+:\d+", a):
            start, stop = (int(q) for q in a.split(":"))
    if "--ceiling" in args:
        ceiling(start, stop)
        return
    rows = run(start, stop)
    report(rows, start, stop)
    if csv:
        keys = sorted({k for r in rows for k in r})
        with open(csv, "w", encoding="utf-8") as fh:
            fh.write(",".join(keys) + "\n")
            for r in rows:
                fh.write(",".join(str(r.get(k, "")) for k in keys) + "\n")


if __name__ == "__main__":
    main()
