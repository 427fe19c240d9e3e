"""The white-noise level of a record (records/segmentation.py ``noise_level``) against its
definition written here on a quantised signal, where the robust (MAD) estimate is 0 and the
trimmed RMS decides (issue 25: on Gaussian noise the MAD decides, which hides the trimming).
Each test names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import numpy as np
import pytest

from dryfriction.records.segmentation import noise_level


def test_quantised_signal_by_definition() -> None:
    # mistakes: the RMS trimmed at the 90 % quantile (the second differences of two quanta
    # dropped); the larger of the two estimates taken as the smaller
    rng = np.random.default_rng(31)
    q = 0.12e-6
    t = np.arange(4000) * 0.05
    x = np.round((1e-3 + 0.24e-6 * t + rng.normal(0.0, 0.1 * q, t.size)) / q) * q
    d2 = np.diff(x, 2)
    mad = 1.4826 * np.median(np.abs(d2 - np.median(d2)))
    a = np.abs(d2)
    rms = np.sqrt(np.mean(a[a <= np.quantile(a, 0.99)] ** 2))
    assert mad == 0.0 < rms  # the case the RMS is there for
    assert noise_level(x) == pytest.approx(max(mad, rms) / np.sqrt(6.0), rel=1e-12)
