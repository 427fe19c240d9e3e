"""The rate-and-state twin of the linear stability: Rice & Ruina's critical stiffness with the
trap model's effective ``a, b, Dc`` (ours: the comparison, not a result of the paper).

It sits above both the theory (:mod:`dryfriction.theory.stability`) and the rate-and-state laws
(:mod:`dryfriction.rsf.law`), which know nothing of each other.
"""

from __future__ import annotations

from ..rsf.law import RateState
from ..theory.direct_stability import effective_rsf_direct
from ..theory.stability import effective_rsf

__all__ = ["rsf_stability_prediction"]


def rsf_stability_prediction(
    u: float,
    eps: float,
    alpha: float = 0.13,
    creep: str = "log",
    mass: float = 0.0,
    damping: float = 0.0,
    direct: float = 0.0,
    v_ref: float = 1.0,
) -> dict[str, float]:
    """Critical stiffness that rate-and-state predicts with the model's effective ``a, b, Dc``.

    Rice & Ruina (1983): ``K_c = (b - a)/Dc [1 + M V^2/(a Dc)]`` (the damping enters as
    ``a -> a + eta V``, see :meth:`dryfriction.rsf.RateState.critical_stiffness`), with
    ``a, b, Dc`` from :func:`~dryfriction.theory.stability.effective_rsf`, in reduced units
    (``K`` in ``F_el/a0``). Compare with
    :func:`~dryfriction.theory.stability.critical_stiffness`: the twin matches the slow response
    only, so the two differ wherever the model's fast response (negative forward stiffness,
    delay at the spinodal edge) matters. With the direct effect (``direct > 0``) the twin's
    ``a`` includes the direct part ``A_u mu_d`` (:func:`.direct_stability.effective_rsf_direct`).
    """
    p = (effective_rsf_direct(u, eps, alpha, creep, direct, v_ref) if direct
         else effective_rsf(u, eps, alpha, creep))
    twin = RateState(a=p["a"], b=p["b"], dc=p["dc"], mu0=1.0, v0=u)
    out = {**p, "K_c": twin.critical_stiffness(u, damping, mass)}
    try:
        out["omega_c"] = twin.hopf_frequency(u, damping)
    except ValueError:
        out["omega_c"] = float("nan")
    return out
