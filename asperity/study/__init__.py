"""Studies: many cases of the pipeline at once, on a Dask cluster, into a resumable store.

* :mod:`.spec` -- study files (what to vary, how to sample it, which stages to run);
* :mod:`.sampling` -- distributions and sample matrices (grid, Monte Carlo, Latin
  hypercube, Saltelli for Sobol indices), reproducible from the seed;
* :mod:`.cases` -- one case through the public API, and a batch of them (the worker's task);
* :mod:`.engine` -- batches on a LocalCluster or an existing Dask cluster, faults, resume;
* :mod:`.store` -- the SQLite result store, export to Parquet and CSV;
* :mod:`.summary` -- probability of ratchet, drift quantiles, Sobol indices, rankings;
  :mod:`.text` and :mod:`.plot` -- its text, summary.md and figures;
* :mod:`.run` -- study file -> summary, the API behind ``asperity study``.
"""
