"""Measured friction records: reading them, finding their load program, cutting them into steps.

The project's own CSV data sets and the types the fitter works on (:mod:`.data`: ``StaticData``,
``SteadyData``, ``SeriesData``); a laboratory record as it comes from the apparatus
(:mod:`.record`: ``LabRecord``), read from text, spreadsheet or MATLAB files (:mod:`.lab`,
:mod:`.labforms`); its load program detected from the displacement (:mod:`.detection`, with
:mod:`.segmentation`, :mod:`.placement`, :mod:`.artifacts`) or given, and its velocity steps
sliced out (:mod:`.labsteps`). Nothing here simulates or fits: ``fit/`` builds on this package.
"""
