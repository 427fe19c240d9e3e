"""The range checks of the fit's value options, shared by :mod:`.fitting` and :mod:`.records`
(each option named as the command line spells it)."""

from __future__ import annotations

__all__ = ["check_fit_options"]


def check_fit_options(*, alpha: float, creep: str, v0: float | None, state_law: str,
                      errors: str, traps_per_a0: float | None, direct: float,
                      v_ref: float) -> None:
    """Every value option of ``fit`` in its range, named as typed, before any work (an
    ``--run-cv --direct -1`` once fitted rsf for 6 s and reported the refusal inside fit.json).

    Raises
    ------
    ValueError
        ``--OPTION VALUE is out of range: allowed ...``.
    """
    from ..ensemble.population import TRAPS_PER_A0_MIN
    from ..ensemble.resources import BYTES_PER_TRAP
    from ..fit.laws import FIT_LAWS
    from ..fit.steps import ERRORS
    from ..rsf.law import V_MAX, V_MIN
    from ..theory.creep import CREEP_LAWS
    from ..validation import ALPHA_MIN, DIRECT_MAX, check_choice, check_memory, check_scalar

    check_scalar("--alpha", alpha, ALPHA_MIN, 1.0, hi_open=True)
    check_choice("--creep", creep, CREEP_LAWS)
    check_choice("--state-law", state_law, (*FIT_LAWS, "auto"))
    check_choice("--errors", errors, ERRORS)
    check_scalar("--direct", direct, 0.0, DIRECT_MAX)
    check_scalar("--v-ref", v_ref, V_MIN, V_MAX)
    if v0 is not None:
        check_scalar("--v0", v0, V_MIN, V_MAX)
    if traps_per_a0 is not None:
        lam = check_scalar("--traps-per-a0", traps_per_a0, TRAPS_PER_A0_MIN)
        # every forward run keeps at least the pairs of 2 (reach + margin + 2) >= 28 a0 around
        # the slider (ensemble.resources.estimate_run): refused here, in the option's name,
        # rather than as a failed evaluation at every trial of the fit
        check_memory(f"--traps-per-a0 {lam:g} keeps at least {28.0 * lam:.1e} pairs around "
                     "the slider in every run of the trap model", 28.0 * lam * BYTES_PER_TRAP,
                     "lower --traps-per-a0")
