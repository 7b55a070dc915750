"""crankbalance: balancing design of reciprocating-engine crank trains."""

from .errors import InputError

__all__ = ["InputError"]
__version__ = "0.1.0"
