"""Every figure (matplotlib object API): the paper's figures (:mod:`.paper`) and the reproduce
report (:mod:`.report`). Nothing outside this package draws."""
