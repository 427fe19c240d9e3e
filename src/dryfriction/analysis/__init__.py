"""Analyses built on the simulators: stick-slip events and classes (:mod:`.stickslip`), the
trap model seen through rate-and-state (:mod:`.rsf_view`)."""
