"""The crankbalance web application (NiceGUI): ``crankbalance web``.

:mod:`.project` holds one user's project (form texts -> engine file -> spec -> results)
without NiceGUI; :mod:`.app` builds the page, one :class:`~.project.Project` per client.
"""
