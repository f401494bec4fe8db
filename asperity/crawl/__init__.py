"""Crawling (issue 26): a slender body that changes shape moves on direction-dependent
friction.  Gaits -- the body's shape in its own frame over one period and the kinematics
the crawl solver reads -- are in :mod:`.gait` (curvature waves and Fourier curvature gaits),
:mod:`.gait_chain` (chains of rigid links: the serpenoid and tables of joint angles),
:mod:`.gait_file` (gait files, TOML) and :mod:`.gait_crossing` (refusing a gait whose body
crosses itself).  Nothing is imported here: ``import asperity`` stays fast."""
