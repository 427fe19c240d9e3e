"""Files: atomic writes and results folders (:mod:`.files`), protocol files (:mod:`.protocol`,
the only parser of protocol dictionaries), the text check every reader of a user's file makes
(:mod:`.textfile`) and the shipped examples (:mod:`.examples`). Laboratory records and data sets
are :mod:`dryfriction.records`; sweeps are :mod:`dryfriction.sweeps`."""
