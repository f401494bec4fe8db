"""``asperity serve``: the pipeline as a local web page, for people who do not write TOML.

From a wedge texture or an uploaded scan to a friction law and a risk verdict in the
browser: FastAPI + uvicorn, pages rendered on the server with Jinja2, plots drawn by
Plotly's own ``plotly.min.js`` served from the installed ``plotly`` package (no CDN, no
JavaScript build).  The pages call the library's public APIs; nothing is computed here.

* :mod:`.settings` -- the server's settings and their checks (loopback unless
  ``--allow-remote``, upload limit, data folder);
* :mod:`.security` -- the access token, Host and Origin checks, the request-size limit;
* :mod:`.store` -- the data folder: uploads under generated names, one folder and one
  JSON record per job, written atomically;
* :mod:`.runner` -- the jobs on worker processes, their progress, restart recovery;
* :mod:`.worker` -- what a worker process runs: one job through the library, its
  progress hooked into :mod:`asperity.progress`, errors as one line; the tasks in
  :mod:`.tasks_surface`, :mod:`.tasks_motion` and :mod:`.tasks_study`, their figures
  (Plotly figure dictionaries) in :mod:`.figures`, plain JSON by :mod:`.results`; the
  job's progress bar, each piece of work in its share and never back, in
  :mod:`.job_progress`;
* :mod:`.forms` -- form fields to numbers, with one-line messages; :mod:`.common` --
  what every form shares (uploads, submitting a job, the form again after an error);
* :mod:`.app` -- the application: errors as one line and a 4xx status, static files,
  the job pages; :mod:`.pages` (Surface, Law) and :mod:`.pages_motion` (Motion and risk,
  Studies) -- the forms of each page, in ``templates/`` with ``static/``;
* :mod:`.server` -- binding the socket and running uvicorn.

Only ``asperity serve`` (:mod:`asperity.cli.serve`) imports this package.
"""
