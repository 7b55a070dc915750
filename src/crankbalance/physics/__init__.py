"""The physics of crankbalance: pure functions on SI arrays and frozen result dataclasses.

Every module here imports numpy, scipy, the standard library, the base modules
(:mod:`crankbalance.errors`, :mod:`crankbalance.results`) and other physics modules only:
no units, no files, no settings, no figures, no edges (``tests/test_architecture.py`` finds
the physics by this folder and holds the rule). docs/architecture.md draws the layers.
"""
