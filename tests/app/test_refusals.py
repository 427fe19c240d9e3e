"""A refusal's stated range excludes the value it refused (the blind review's survivor
``apptheory_range_units``: the --V range printed in reduced units times the wrong scale, so
"--V 1e+30 m/s is out of range ... allowed 1e-27 to 1e+33 m/s")."""

from __future__ import annotations

import re

import pytest

from dryfriction.app.theory import steady


@pytest.mark.parametrize("V", [3.7e30, 2.9e-40])
def test_steady_velocity_refusal_states_a_range_that_excludes_it(V: float) -> None:
    a0, t0 = 2.3e-6, 4.1e-3  # V* = a0/t0 = 5.6e-4 m/s
    with pytest.raises(ValueError) as info:
        steady(0.037, V=[1.1e-6, V], a0=a0, t0=t0)
    msg = str(info.value)
    m = re.search(r"allowed (\S+) to (\S+) m/s", msg)
    assert m is not None and "--V" in msg, msg
    lo, hi = float(m.group(1)), float(m.group(2))
    assert lo < 1.1e-6 < hi, msg  # the accepted value lies inside
    assert not (lo <= V <= hi), msg
    from dryfriction.validation import U_MAX, U_MIN
    assert (lo, hi) == pytest.approx((U_MIN * a0 / t0, U_MAX * a0 / t0), rel=1e-3)


def test_bifurcation_checks_at_most_max_checked_velocities(tmp_path) -> None:
    """Exactly MAX_CHECKED velocities with check=True are allowed, one more is refused, both
    before any work (a missing protocol shows which refusal came first). The mistake this
    is for: ``>=`` for ``>``, which refused 12 with "allowed at most 12"."""
    from dryfriction.analysis.hopf_table import MAX_CHECKED
    from dryfriction.app.hopf import bifurcation

    missing = tmp_path / "missing.toml"
    for n, refused in ((MAX_CHECKED, False), (MAX_CHECKED + 1, True)):
        vs = [1.3e-6 * 1.7 ** i for i in range(n)]
        with pytest.raises((ValueError, OSError)) as info:
            bifurcation(missing, vs, tmp_path / "out", check=True)
        assert ("allowed at most" in str(info.value)) is refused, str(info.value)
    assert not (tmp_path / "out").exists()
