"""python -m crankbalance: the command line."""

from .cli import main

main()
