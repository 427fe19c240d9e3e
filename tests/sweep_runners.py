"""Runners for the sweep tests (shipped to the Dask workers by value)."""

import os
import time
from pathlib import Path


def counting_runner(protocol):
    """x * y, leaving a marker file per call so the test can count computations."""
    t = protocol["test"]
    Path(t["markers"], f"{os.getpid()}-{time.monotonic_ns()}").touch()
    time.sleep(t.get("sleep", 0.0))
    if t["x"] == 3 and t.get("fail_at_3", False):
        raise RuntimeError("boom at x = 3")
    return {"product": t["x"] * t["y"], "sum": t["x"] + t["y"]}


def other_runner(protocol):
    """A different analysis of the same protocol (x - y)."""
    t = protocol["test"]
    return {"difference": t["x"] - t["y"]}
