"""The rate-and-state twin of the linear stability: Rice & Ruina's critical stiffness with the
trap model's effective ``a, b, Dc`` (ours: the comparison, not a result of the paper).

It sits above both the theory (:mod:`dryfriction.theory.linear_stability`) and the
rate-and-state laws (:mod:`dryfriction.rsf.law`), which know nothing of each other.
"""

from __future__ import annotations

from ..rsf.law import RateState
from ..theory.linear_stability import effective_rsf
from ..theory.model import TrapModel

__all__ = ["rsf_stability_prediction"]


def rsf_stability_prediction(
    u: float, model: TrapModel, mass: float = 0.0, damping: float = 0.0,
) -> dict[str, float]:
    """Critical stiffness that rate-and-state predicts with the model's effective ``a, b, Dc``.

    Rice & Ruina (1983): ``K_c = (b - a)/Dc [1 + M V^2/(a Dc)]`` (the damping enters as
    ``a -> a + eta V``, see :meth:`dryfriction.rsf.RateState.critical_stiffness`), with
    ``a, b, Dc`` from :func:`~dryfriction.theory.linear_stability.effective_rsf`, in reduced
    units (``K`` in ``F_el/a0``). Compare with
    :func:`~dryfriction.theory.linear_stability.critical_stiffness`: the twin matches the slow
    response only, so the two differ wherever the model's fast response (negative forward
    stiffness, delay at the spinodal edge) matters. With the direct effect (``model.direct >
    0``) the twin's ``a`` includes the direct part ``A_u mu_d``.
    """
    p = effective_rsf(u, model)
    twin = RateState(a=p["a"], b=p["b"], dc=p["dc"], mu0=1.0, v0=u)
    out = {**p, "K_c": twin.critical_stiffness(u, damping, mass)}
    try:
        out["omega_c"] = twin.hopf_frequency(u, damping)
    except ValueError:
        out["omega_c"] = float("nan")
    return out
