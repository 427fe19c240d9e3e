"""Files: atomic writes and results folders (:mod:`.files`), protocol files (:mod:`.protocol`,
the only parser of protocol dictionaries), measured data (:mod:`.data`), sweeps on Dask
(:mod:`.sweep`)."""
