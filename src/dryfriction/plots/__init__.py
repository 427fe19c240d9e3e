"""Every figure (matplotlib object API, no pyplot): the paper's figures (:mod:`.paper`), the
figures of runs and sweeps (:mod:`.runs`), the reproduce report (:mod:`.report`), in the one
style of :mod:`.style`. Nothing outside this package draws."""
