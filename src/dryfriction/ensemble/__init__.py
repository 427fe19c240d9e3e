"""The time-dependent trap ensemble: the hysteron population and its compiled kernel
(:mod:`.population`) and the drives that move it (:mod:`.driving`: velocity programs, force
control, spring sliders)."""
