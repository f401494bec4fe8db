"""Crawling (issue 26): bodies that change shape move on direction-dependent friction.

:mod:`.gait` (and :mod:`.gait_chain`, :mod:`.gait_file`, :mod:`.gait_crossing`) the gaits,
:mod:`.solver` the crawl (``asperity.crawling``), :mod:`._kernels` its numba step loop,
:mod:`.output` its JSON, CSV and plot.  Nothing heavy is imported here."""
