"""The trap ensemble in time: a population of hysterons on a track (docs/model.md §6).

Reduced units: lengths in ``a0``, times in ``t0``, forces per trap in ``Phi00/a0``, the total
friction force in ``F_el`` (eq. 12).

Model (docs/model.md §6; every choice below is ours unless an equation is cited)
--------------------------------------------------------------------------------
* Asperity pairs sit at fixed track positions ``c_i`` with density ``lambda`` per ``a0``
  (``traps_per_a0``), either on a regular lattice ``c_k = (k + 1/2)/lambda`` (the half offset keeps
  a pair off the Maxwell point ``p = 0`` of the rest state) or uniformly at random, ``1024`` pairs
  per block of length ``1024/lambda``, block ``b`` drawn from ``SeedSequence([seed, b'])`` so the
  track is the same however far a run goes. The configuration coordinate is ``p_i = X - c_i``.
* Each pair is a hysteron with four states: free on the near side (``p < -1``), on the (+)
  branch, on the (-) branch, free on the far side. An active trap carries its birth time
  ``t_b``; its radius ratio is ``r = a_r(t - t_b)`` (eq. 19) and, with ``w = p/r``, its force
  ``r^2 f_+(w)`` on (+), ``r^2 f_-(w)`` on (-) (eq. 23). Total friction
  ``F/F_el = sum_i f_i / (lambda H0)`` (eq. 12 with density ``lambda`` per ``a0``).
* Transitions, in the trap's own units ``w``:

  - free-near -> (+) when ``p`` reaches ``-1`` moving forward. **[model choice]** A pair that
    enters contact, including one that re-enters, starts *fresh*: radius 1, birth time = the
    time it crossed ``p = -1`` (interpolated linearly within a step);
  - (+) at ``w > y_c``: dies (very strong pinning, ``alpha < alpha0``) or jumps to (-) keeping
    its birth time (strong pinning);
  - (-) at ``w > 1``: leaves contact (zero force, free-far);
  - backwards: (+) at ``w < -1`` leaves contact (free-near, zero force); (-) at ``w < -y_c``
    jumps to (+) if ``-y_c >= -1`` (strong pinning) else dies; free-far -> (-) entering fresh
    at ``p = +1`` moving backwards.

  Free traps do not age (docs/model.md §2). During ageing at fixed ``p``, ``|w|`` shrinks, so a hold
  causes no transition and costs one step whatever its length.
* Initial states (all births at ``t = 0`` unless said): ``rest`` (eq. 25: (+) on
  ``[-1, 0)``, (-) on ``[0, 1]``); ``loaded`` (edge at ``d_w`` where the fresh force equals
  ``f_w``, :func:`dryfriction.theory.static.loaded_edge`: (+) on ``[-1, d_w)``, (-) on ``[d_w,
  1]``); ``steady`` at velocity ``u`` (eq. 29: (+) on ``[-1, p_d]`` with birth ``-(p + 1)/u``, in
  strong pinning continued on (-) up to ``w = 1``).

Numerics
--------
Only a window of pairs around the slider is touched, by one Numba-compiled loop (:mod:`.kernel`,
which describes the window and the radius table).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Literal

import numpy as np

from .. import simulation
from ..interrupts import deferred
from ..theory.model import TRAPS_PER_A0, TrapModel
from ..theory.static import loaded_edge
from ..theory.trap import Regime
from ..validation import (
    U_MAX,
    U_MIN,
    Array,
    check_choice,
    check_scalar,
)
from .kernel import FREE_FAR, FREE_NEAR, MINUS, OUT_SIZE, PLUS, advance_window, radius_table

__all__ = [
    "FREE_NEAR",
    "PLUS",
    "MINUS",
    "FREE_FAR",
    "TrapModel",
    "Track",
    "Initial",
    "Observables",
    "Ensemble",
]


LAYOUTS: tuple[str, ...] = ("regular", "random")
TRAPS_PER_A0_MIN: float = TRAPS_PER_A0.lo  # type: ignore[assignment]
"""Sparsest track accepted (pairs per ``a0``): :data:`dryfriction.theory.model.TRAPS_PER_A0`."""
INITIAL_KINDS: tuple[str, ...] = ("rest", "loaded", "steady")
_BLOCK = 1024  # pairs per random block
_CHUNK = 1 << 16
"""Pairs placed at once by ``Ensemble._place_initial``: its temporaries (about 50 bytes a
pair for a steady population) are then bounded, and the start-up peak is the 17 bytes a pair
the buffer holds (position, birth, state) plus a few MB."""


@dataclass(frozen=True)
class Track:
    """Positions ``c`` of the asperity pairs along the track, indexed by a global integer ``k``.

    Parameters
    ----------
    traps_per_a0 : float
        Density ``lambda`` of pairs per ``a0`` of track, ``>= 1e-6`` (a sparser track has no
        pair within any run's reach, and its spacing overflows the index arithmetic).
    layout : {"regular", "random"}
        ``c_k = (k + 1/2)/lambda``, or seeded uniform positions, 1024 per block of length
        ``1024/lambda`` (sorted within a block).
    seed : int, optional
        Required for ``layout = "random"``; a non-negative integer.
    """

    traps_per_a0: float
    layout: str = "regular"
    seed: int | None = None

    def __post_init__(self) -> None:
        lam = check_scalar("traps_per_a0", self.traps_per_a0, TRAPS_PER_A0_MIN)
        object.__setattr__(self, "traps_per_a0", lam)
        check_choice("layout", self.layout, LAYOUTS)
        if self.layout == "random":
            if self.seed is None:
                raise ValueError("seed is required for layout = 'random' (random positions "
                                 "come from an explicit seed)")
        if self.seed is not None:
            if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)):
                raise ValueError(f"seed = {self.seed!r} is not allowed: a non-negative integer")
            if self.seed < 0:
                raise ValueError(f"seed = {self.seed} is out of range: allowed >= 0")

    @property
    def spacing(self) -> float:
        """Mean distance between pairs, ``1/lambda`` (units ``a0``)."""
        return 1.0 / self.traps_per_a0

    def index_span(self, c_lo: float, c_hi: float) -> tuple[int, int]:
        """Global indices ``[k0, k1)`` of a stretch that contains every pair in ``[c_lo, c_hi]``."""
        lam = self.traps_per_a0
        if self.layout == "regular":
            return math.floor(c_lo * lam - 0.5) - 1, math.ceil(c_hi * lam - 0.5) + 2
        L = _BLOCK / lam
        return math.floor(c_lo / L) * _BLOCK, (math.floor(c_hi / L) + 1) * _BLOCK

    def positions(self, k0: int, k1: int) -> Array:
        """Positions ``c_k`` for ``k0 <= k < k1``, ascending, units ``a0``."""
        lam = self.traps_per_a0
        if self.layout == "regular":
            c = np.arange(k0, k1, dtype=float)
            c += 0.5  # in place: one array of 8 bytes a pair at the peak, not two
            c /= lam
            return c
        L = _BLOCK / lam
        b0, b1 = k0 // _BLOCK, (k1 - 1) // _BLOCK + 1
        parts = []
        for b in range(b0, b1):
            zig = 2 * b if b >= 0 else -2 * b - 1  # SeedSequence wants non-negative words
            rng = np.random.default_rng(np.random.SeedSequence([int(self.seed or 0), zig]))
            parts.append((b + np.sort(rng.random(_BLOCK))) * L)
        allc = np.concatenate(parts)
        return allc[k0 - b0 * _BLOCK : k1 - b0 * _BLOCK]


@dataclass(frozen=True)
class Initial(simulation.Initial):
    """The contact population at ``t = 0``: which pairs are in contact, how old, and where
    the pairs sit on the track.

    The track belongs here, not to the :class:`TrapModel`: the model is the law of one trap
    (stiffness, creep, direct effect), which the theory (:mod:`dryfriction.theory`) uses for
    the continuum of traps, where the pairs have no positions; the track is one realisation
    of the population (a density, a layout, a seed), as the state is for rate-and-state
    (:class:`dryfriction.rsf.spring.RSFInitial`). So the same model serves the theory and
    every run, and two runs on the same track differ only in how they start.

    Parameters
    ----------
    kind : {"rest", "loaded", "steady"}
        Contact made at rest under zero load (eq. 25), under a tangential force ``force``, or
        the steady-sliding population at velocity ``velocity`` (eq. 29).
    force : float, optional
        ``loaded`` only: the tangential force during contact formation, units ``F_el``,
        ``-1 < force < 1`` (a negative force is the reversed load, the mirror image).
    velocity : float, optional
        ``steady`` only: the reduced sliding velocity ``u > 0`` (units ``a0/t0``).
    track : Track
        Positions of the asperity pairs, required by a run
        (:func:`dryfriction.ensemble.driving.simulate`); ``None`` only for the old form of the
        call, which passes the track on its own, and for an :class:`Ensemble`, which takes it
        as its own argument.
    """

    law: ClassVar[str] = "cv"
    kind: str = "rest"
    force: float | None = None
    velocity: float | None = None
    track: Track | None = None

    def __post_init__(self) -> None:
        if self.track is not None and not isinstance(self.track, Track):
            raise ValueError(f"track = {self.track!r} is not allowed: a Track (the pairs' "
                             "density traps_per_a0, layout and seed)")
        check_choice("initial", self.kind, INITIAL_KINDS)
        if self.kind == "loaded":
            if self.force is None:
                raise ValueError("initial_force is required for initial = 'loaded'")
            f = check_scalar("initial_force", self.force, -1.0, 1.0, lo_open=True, hi_open=True)
            object.__setattr__(self, "force", f)
        elif self.force is not None:
            raise ValueError(f"initial_force applies only to initial = 'loaded', "
                             f"not {self.kind!r}")
        if self.kind == "steady":
            if self.velocity is None:
                raise ValueError("initial_velocity is required for initial = 'steady'")
            v = check_scalar("initial_velocity", self.velocity, U_MIN, U_MAX)
            object.__setattr__(self, "velocity", v)
        elif self.velocity is not None:
            raise ValueError(f"initial_velocity applies only to initial = 'steady', "
                             f"not {self.kind!r}")


@dataclass(frozen=True)
class Observables:
    """What one ensemble step measures (units: ``F_el``, ``F_el/a0``, ``t0``).

    Attributes
    ----------
    force : float
        Friction force ``F/F_el`` (without ``mu_el``).
    stiffness : float
        ``dF/dX`` at frozen ages, units ``F_el/a0`` (diverges where a trap nears its spinodal);
        computed only when asked (``probe(..., stiffness=True)``), else 0.
    n_active : int
        Traps in contact.
    mean_age : float
        Mean age of the traps in contact (NaN if none), units ``t0``.
    births, spinodal, exits : int
        Pairs entering contact; traps reaching a spinodal (death in very strong pinning, jump
        to the other branch in strong pinning, both force discontinuities); traps leaving
        contact at zero force (``w = 1`` on (-), ``w = -1`` on (+)). Counted during the step.
    next_event : float
        Frozen-age slider position of the next spinodal in the step's direction (``+-inf``
        if none): where the force jumps next.
    """

    force: float
    stiffness: float
    n_active: int
    mean_age: float
    births: int
    spinodal: int
    exits: int
    next_event: float


# ---------------------------------------------------------------- the population


class Ensemble:
    """The state of the trap population and the operations on it (mutable by design).

    Parameters
    ----------
    model : TrapModel
        Trap and creep parameters.
    track : Track
        Positions of the pairs.
    initial : Initial
        Initial population, made at ``t = 0`` with the slider at ``x0``.
    x0 : float
        Initial slider position (units ``a0``).
    age_horizon : float
        Largest trap age (``t0``) the radius table must cover at first; extended on demand.

    Notes
    -----
    The buffer holds the pairs with global indices ``[g0, g0 + n)``; the window ``[lo, hi)``
    (buffer indices) contains every pair in contact. Pairs outside it are free.
    """

    def __init__(
        self,
        model: TrapModel,
        track: Track,
        initial: Initial,
        x0: float = 0.0,
        age_horizon: float = 1.0,
    ) -> None:
        self.model = model
        self.track = track
        self.initial = initial
        trap = model.trap
        self._alpha = model.alpha
        self._yc = trap.y_c
        self._strong = trap.regime is Regime.STRONG
        self._norm = 1.0 / (track.traps_per_a0 * trap.H0)
        self._law = model.law
        self.x = float(x0)
        self.t = 0.0
        self._out = np.zeros(OUT_SIZE)
        self._oldest_birth = 0.0
        self._margin = 8.0 + 2.0 * max(1.0, self._yc)
        self._place_initial()
        self._build_table(max(age_horizon, 1.0) - self._oldest_birth)

    # -- read-only views for the drives
    @property
    def force_scale(self) -> float:
        """Factor from a per-trap force (``Phi00/a0``) to ``F/F_el``: ``1/(lambda H0)`` (eq. 12)."""
        return self._norm

    @property
    def y_c(self) -> float:
        """Spinodal threshold ``y_c`` of the traps, in the trap's own units ``w``."""
        return self._yc

    @property
    def oldest_birth(self) -> float:
        """Earliest birth (``t0``, ``<= 0``) of any trap: ``t - oldest_birth`` bounds every age."""
        return self._oldest_birth

    # -- radius table
    def _build_table(self, age_max: float) -> None:
        """Tabulate ``a_r^2`` up to at least ``age_max`` (:func:`.kernel.radius_table`)."""
        self._h, self._s_tab, self._ds_tab, self._age_cover = radius_table(self._law, age_max)

    def radius(self, age: Array) -> Array:
        """``a_r(age)`` from the creep law (exact functions, not the table)."""
        return self._law.radius(np.asarray(age, float))

    # -- buffer
    def _set_buffer(self, k0: int, k1: int) -> None:
        self._g0 = k0
        self.c = self.track.positions(k0, k1)
        self.state = np.zeros(k1 - k0, dtype=np.int8)
        self.birth = np.zeros(k1 - k0)

    def _place_initial(self) -> None:
        ini = self.initial
        yc = self._yc
        D = max(1.0, yc)
        reach = D
        if ini.kind == "steady":  # where the oldest trap leaves contact: p = D a_r((p + 1)/u)
            for _ in range(100):
                reach = min(D * float(self.radius((reach + 1.0) / float(ini.velocity or 1))), 1e3)
        reach += 1.0
        k0, k1 = self.track.index_span(self.x - reach - self._margin, self.x + reach + self._margin)
        self._set_buffer(k0, k1)
        d = 0.0 if ini.kind != "loaded" else loaded_edge(self.model, float(ini.force or 0.0))
        u = float(ini.velocity or 1.0)
        lo = hi = -1
        carry = -np.inf  # running maximum of w over the higher indices (steady only)
        # chunk by chunk from the high-index end, where the steady population's running
        # maximum starts: the same values as one pass over the whole buffer, in bounded memory
        for j1 in range(self.c.size, 0, -_CHUNK):
            j0 = max(j1 - _CHUNK, 0)
            p = self.x - self.c[j0:j1]
            st = np.where(p < -1.0, FREE_NEAR, FREE_FAR).astype(np.int8)
            if ini.kind in ("rest", "loaded"):
                plus = (p >= -1.0) & (p < d) & (p <= yc)
                minus = (p >= d) & (p <= 1.0) & (p >= -yc)
                st[plus] = PLUS
                st[minus] = MINUS
                self.birth[j0:j1] = 0.0
            else:
                inside = p >= -1.0
                age = np.where(inside, (p + 1.0) / u, 0.0)
                w = p / self.radius(age)
                # a trap is alive if w never exceeded the threshold over its past; p descends
                # with the index, so the running maximum runs from the high index end
                w_rev = np.where(inside, w, -np.inf)[::-1]
                w_rev[0] = max(w_rev[0], carry)
                wmax = np.maximum.accumulate(w_rev)[::-1]
                carry = wmax[0]
                plus = inside & (wmax <= yc)
                st[plus] = PLUS
                if self._strong:
                    minus = inside & (wmax > yc) & (wmax <= 1.0)
                    st[minus] = MINUS
                self.birth[j0:j1] = np.where(inside, -age, 0.0)
            self.state[j0:j1] = st
            active = np.flatnonzero((st == PLUS) | (st == MINUS))
            if active.size:
                if hi < 0:
                    hi = j0 + int(active[-1]) + 1
                lo = j0 + int(active[0])
                self._oldest_birth = min(self._oldest_birth,
                                         float(self.birth[j0:j1][active].min()))
        if hi >= 0:
            self.lo, self.hi = lo, hi
        else:
            k = int(np.searchsorted(self.c, self.x + 1.0, side="right"))
            self.lo = self.hi = k

    def _ensure_cover(self, x_lo: float, x_hi: float) -> None:
        """Make the buffer hold every pair with ``c`` in ``[x_lo - 1, x_hi + 1]`` plus margin."""
        c = self.c
        need_lo, need_hi = x_lo - 1.0 - 1.0, x_hi + 1.0 + 1.0
        if c[0] < need_lo and c[-1] > need_hi and self.lo > 0 and self.hi < len(c):
            return
        m = self._margin
        k0, k1 = self.track.index_span(need_lo - m, need_hi + m)
        g_lo, g_hi = self._g0 + self.lo, self._g0 + self.hi
        k0 = min(k0, g_lo - 1)
        k1 = max(k1, g_hi + 1)
        # only the window (the pairs in contact) carries over: copy it, and let the old
        # buffer go before the new one is made, so that a move holds one buffer, not two
        old = slice(self.lo, self.hi)
        win_state, win_birth = self.state[old].copy(), self.birth[old].copy()
        del c
        self.c, self.state, self.birth = np.empty(0), np.empty(0, np.int8), np.empty(0)
        self._set_buffer(k0, k1)
        self.state[: g_lo - k0] = FREE_FAR  # no index array either
        self.state[g_lo - k0 :] = FREE_NEAR
        sl = slice(g_lo - k0, g_hi - k0)
        self.state[sl] = win_state
        self.birth[sl] = win_birth
        self.lo, self.hi = g_lo - k0, g_hi - k0

    def cover(self, x_lo: float, x_hi: float) -> None:
        """Hold in the buffer every pair a slider anywhere in ``[x_lo, x_hi]`` (``a0``) can
        touch: a caller that steps the compiled kernel itself (the extended interface,
        :mod:`.interface`) places the pairs once for its whole run."""
        self._ensure_cover(float(x_lo), float(x_hi))

    def _ensure_ages(self, t: float) -> None:
        if t - self._oldest_birth > self._age_cover:
            self._build_table(2.0 * (t - self._oldest_birth))

    # -- the two operations
    def _call(self, x1: float, t1: float, direction: int, commit: bool,
              stiffness: bool = False) -> Observables:
        self._ensure_cover(min(self.x, x1), max(self.x, x1))
        self._ensure_ages(t1)
        args = (self.c, self.state, self.birth, self.lo, self.hi, self.x, x1, self.t, t1,
                direction, self._alpha, self._yc, self._strong, self._h, self._s_tab,
                self._ds_tab, commit, stiffness, self._out)
        if advance_window.overloads:  # loaded; it returns two ints: no guard needed
            lo, hi = advance_window(*args)
        else:  # the first call loads (or compiles) it: signals held back meanwhile
            with deferred():
                lo, hi = advance_window(*args)
        o = self._out
        if o[8] != 0.0:  # pragma: no cover - the cover margin makes this unreachable
            raise RuntimeError("ensemble window reached the end of its buffer")
        if commit:
            self.lo, self.hi = int(lo), int(hi)
            self.x, self.t = float(x1), float(t1)
        n = int(o[2])
        return Observables(
            force=float(o[0]) * self._norm,
            stiffness=float(o[1]) * self._norm,
            n_active=n,
            mean_age=float(o[3]) / n if n else math.nan,
            births=int(o[4]),
            spinodal=int(o[5]),
            exits=int(o[6]),
            next_event=float(o[7]),
        )

    def advance(self, x1: float, t1: float) -> Observables:
        """Move the slider linearly from its position to ``x1`` while time runs to ``t1``.

        Parameters
        ----------
        x1 : float
            New slider position (``a0``).
        t1 : float
            New time (``t0``), ``>= self.t``.

        Returns
        -------
        Observables
            Measured at ``(x1, t1)``; counts are those of the step.
        """
        if t1 < self.t:
            raise ValueError(f"t1 = {t1:g} is before the ensemble time {self.t:g}")
        direction = 1 if x1 >= self.x else -1
        return self._call(float(x1), float(t1), direction, True)

    def probe(self, x1: float, direction: int | None = None, *,
              stiffness: bool = False) -> Observables:
        """Observables if the slider moved to ``x1`` at frozen ages, without changing anything;
        with ``stiffness``, ``dF/dX`` too (else its field is 0)."""
        if direction is None:
            direction = 1 if x1 >= self.x else -1
        return self._call(float(x1), self.t, direction, False, stiffness)

    def observe(self, direction: int = 1, *, stiffness: bool = False) -> Observables:
        """Observables of the present state (``next_event`` in ``direction``; ``dF/dX`` with
        ``stiffness``)."""
        return self.probe(self.x, direction, stiffness=stiffness)

    def snapshot(self) -> dict[str, Array]:
        """The pairs in contact: ``p`` (``a0``), ``branch`` (+1/-1), ``age`` (``t0``),
        ``radius`` (``a0``), ``force`` (units ``Phi00/a0``, eq. 23)."""
        sl = slice(self.lo, self.hi)
        st = self.state[sl]
        act = (st == PLUS) | (st == MINUS)
        p = (self.x - self.c[sl])[act]
        age = self.t - self.birth[sl][act]
        r = self.radius(age)
        branch = np.where(st[act] == PLUS, 1.0, -1.0)
        from ..theory.trap import force_minus, force_plus

        w = p / r
        f = np.where(branch > 0, force_plus(np.minimum(w, self._yc), self._alpha),
                     force_minus(np.maximum(w, -self._yc), self._alpha))
        return {"p": p, "branch": branch, "age": age, "radius": r, "force": r * r * f}


_InitialKind = Literal["rest", "loaded", "steady"]
