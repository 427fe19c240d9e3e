"""The range checks of the fit's value options, shared by :mod:`.fitting` and :mod:`.records`
(each option named as the command line spells it)."""

from __future__ import annotations

from typing import Any

__all__ = ["check_fit_options", "not_applicable", "check_fit_applies", "check_record_applies"]


def not_applicable(flag: str, value: str, only: str, why: str, remedy: str) -> ValueError:
    """The one-line refusal of an option given where it does not apply (read and ignored, it
    looks obeyed): ``--u-ref 2 applies only with --direct > 0 (why): give --direct or drop
    --u-ref``. ``value`` as typed ("" for a flag without one)."""
    shown = f"{flag} {value}" if value else flag
    return ValueError(f"{shown} applies only {only} ({why}): {remedy}")


def _given(options: dict[str, Any], defaults: dict[str, Any]) -> Any:
    """``given(name)``: the option differs from its default (was typed)."""
    return lambda name: options[name] is not None and options[name] != defaults[name]


def _typed(options: dict[str, Any]) -> Any:
    """``typed(name)``: ``(flag, value)`` as the command line spells the option given."""
    def typed(name: str) -> tuple[str, str]:
        v = options[name]
        if isinstance(v, bool):  # a switch: its own spelling
            on, off = {"trend": ("--trend", "--no-trend"),
                       "compare": ("--compare", "--no-compare")}.get(
                name, (f"--{name.replace('_', '-')}", f"--no-{name.replace('_', '-')}"))
            return (on if v else off), ""
        return f"--{name.replace('_', '-')}", f"{v:g}" if isinstance(v, float) else str(v)

    return typed


def check_record_applies(options: dict[str, Any], defaults: dict[str, Any]) -> None:
    """Refuse, in one line naming it, an option of ``fit`` that a laboratory record's fit does
    not use, before any work (``fit RECORD --traps-per-a0 50 --alpha 0.2`` fitted rsf, exit
    0): the trap model's options without ``--run-cv`` (``--alpha``, ``--creep``, ``--direct``,
    ``--v-ref``, ``--traps-per-a0``; ``--model cv`` is refused with its cost estimate), and
    ``--regularized`` and ``--no-compare``, which only the project's CSV files read."""
    given, typed = _given(options, defaults), _typed(options)
    if not options["run_cv"] and options["model"] != "cv":
        for name in ("alpha", "creep", "direct", "v_ref", "traps_per_a0"):
            if given(name):
                flag, value = typed(name)
                raise not_applicable(flag, value, "to a trap-model fit", "on a record: "
                                     "--run-cv; this run fits rate-and-state alone",
                                     f"drop {flag} or add --run-cv")
    for name, why in (("regularized", "a record's steps take the regularised law across a "
                       "hold and the standard one at a velocity step"),
                      ("compare", "a record's comparison with the trap model is --run-cv")):
        if given(name):
            flag, value = typed(name)
            raise not_applicable(flag, value, "to the project's CSV files", why,
                                 f"drop {flag}")


_KIND_WORDS = {"static": "static friction (t_w,mu_s)", "steady": "steady friction (V,mu_d)",
               "series": "a time series (t,v_load,mu)"}


def check_fit_applies(options: dict[str, Any], defaults: dict[str, Any], kinds: set[str],
                      sources: list[str]) -> None:
    """Refuse, in one line naming it, an option of ``fit`` on the project's CSV files that
    the data kinds (``kinds``) or the models fitted do not use, before any fit (a second new
    user's ``fit steady.csv --stiffness 5 --trend --traps-per-a0 50`` ran, exit 0).

    * ``--stiffness``, ``--trend/--no-trend``: the machine of a time series; static and
      steady friction are measured without it.
    * ``--traps-per-a0``: the trap model's simulated ensemble, run for time series only
      (static and steady friction are its integrals, eqs. 27 and 34).
    * ``--state-law`` on steady data alone: every law's steady state is
      ``mu0 + (a - b) ln(V/V0)`` (Ruina 1983), so the fit is the same.
    * rate-and-state options (``--v0``, ``--state-law``, ``--regularized``) where only the trap
      model is fitted (``--model cv --no-compare``), the trap model's (``--alpha``,
      ``--creep``, ``--direct``, ``--v-ref``, ``--traps-per-a0``) where only rate-and-state
      is; ``--v-ref`` without ``--direct``; ``--direct`` with static data (the model raises
      it too, in its own words: the threshold needs the pull velocity).

    ``options`` and ``defaults`` are keyed as :data:`dryfriction.app.options.OPTIONS`
    ``["fit"]``; an option is given where it differs from its default.
    """
    given, typed = _given(options, defaults), _typed(options)
    held = " and ".join(sorted(_KIND_WORDS[k] for k in kinds if k != "series"))
    files = ", ".join(sources)
    if "series" not in kinds:
        for name, why in (("stiffness", "the machine's spring: {files} hold(s) {held}, "
                           "measured without it"),
                          ("trend", "the machine's drift: {files} hold(s) {held}, measured "
                           "without it"),
                          ("traps_per_a0", "the trap model's simulated ensemble: {files} "
                           "hold(s) {held}, its integral (eqs. 27, 34), not simulated")):
            if given(name):
                flag, value = typed(name)
                raise not_applicable(flag, value, "to a time series (t,v_load,mu)",
                                     why.format(files=files, held=held), f"drop {flag}")
    if kinds == {"steady"} and given("state_law"):
        raise not_applicable("--state-law", options["state_law"], "to static or time-series "
                             "data", f"{files} hold(s) steady friction, mu0 + (a - b) "
                             "ln(V/V0) for every state law (Ruina 1983)",
                             "drop --state-law")
    model = options["model"]
    fitted = {model, *({"cv", "rsf"} - {model} if options["compare"] else ())}
    for other, names, words in (("rsf", ("v0", "state_law", "regularized"),
                                 "a rate-and-state fit"),
                                ("cv", ("alpha", "creep", "direct", "v_ref", "traps_per_a0"),
                                 "a trap-model fit")):
        if other in fitted:
            continue
        for name in names:
            if given(name):
                flag, value = typed(name)
                raise not_applicable(flag, value, f"to {words}", f"--model {other}, or the "
                                     f"comparison --compare; this run fits --model {model} "
                                     "alone", f"drop {flag} or --no-compare")
    if "static" in kinds and "cv" in fitted and given("direct"):
        flag, value = typed("direct")
        raise not_applicable(flag, value, "to steady or time-series data", f"{files} hold(s) "
                             "static friction: with the direct effect the threshold depends "
                             "on the pull velocity, which a t_w,mu_s file does not give",
                             f"drop {flag}, or fit the static file without it")
    if given("v_ref") and not options["direct"]:
        flag, value = typed("v_ref")
        raise not_applicable(flag, value, "with --direct > 0", "the direct effect's "
                             "reference velocity, m/s", "give --direct or drop --v-ref")


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
