"""Batch studies: many cases (headings × sea states × speeds …), run on Dask.

* :mod:`~cummins.studies.study`: a study's definition (cases, limits, scatter diagram);
* :mod:`~cummins.studies.batch`: running it and gathering per-case statistics;
* :mod:`~cummins.studies.operability`: limits applied to the results, operability.
"""
