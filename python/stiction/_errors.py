"""The exceptions of the package: the model library's two categories of failure.

Every error the library reports carries a category (``contact_core::Category``): bad input
(a scene key, a value outside its domain, an argument) or a numerical failure (a solver
that did not converge). The command line maps them to exit status 2 and 1; this package
maps them to :class:`InputError` and :class:`NumericalError`, both :class:`StictionError`.
The message is the library's, word for word (it names the file, the key, the value and
what is allowed).
"""

from __future__ import annotations


class StictionError(Exception):
    """Base class of every error the stiction model reports.

    Attributes:
        category: ``"input"`` or ``"numerical"``.
        key: the scene key the error is about (``"surface.sigma_s"``), if any.
    """

    category: str = ""

    def __init__(self, message: str, key: str | None = None) -> None:
        super().__init__(message)
        self.key = key


class InputError(StictionError, ValueError):
    """Bad input: a scene that cannot be read or parsed, an unknown or missing key, a
    value outside its domain, an argument outside its range (exit status 2 of the CLI).
    Also a ``ValueError``."""

    category = "input"


class NumericalError(StictionError, RuntimeError):
    """A numerical failure of the model on valid input (exit status 1 of the CLI).
    Also a ``RuntimeError``."""

    category = "numerical"


for _cls in (StictionError, InputError, NumericalError):
    _cls.__module__ = "stiction"
