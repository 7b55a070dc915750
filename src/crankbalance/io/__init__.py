"""Every file format of crankbalance, one module each, at the edge of the package.

``engine_file`` (engine TOML/JSON and the presets), ``files`` (atomic writes). Physics
modules never import this package.
"""
