"""Parameter sweeps on Dask: the sweep itself (:mod:`.sweep`), the local cluster it runs on
(:mod:`.cluster`) and the CF attributes of its ``sweep.nc`` (:mod:`.cf`)."""
