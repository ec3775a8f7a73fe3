"""grain's Python layer.

`grain._grain` holds the compiled models (pybind11); `grain.parmec` runs Parmec input decks on
them (the command `grain-parmec DECK.py [ARGS...]`). Units are SI throughout.
"""
from ._grain import InputError, NumericalError  # noqa: F401

__all__ = ["InputError", "NumericalError"]
