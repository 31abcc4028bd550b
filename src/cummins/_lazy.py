"""Names of a package imported from its modules on first use (PEP 562), so that importing
the package for one of its parts does not load the others (``cummins.io.detect_format``
asks every format package for its detection function only)."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy_attributes(
    package: str, lazy: Mapping[str, str], namespace: dict[str, Any]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The module functions ``__getattr__`` and ``__dir__`` of ``package``.

    Parameters
    ----------
    package
        The package's ``__name__``.
    lazy
        Each name → the module of the package it lives in (``"read_mss": "reader"``).
    namespace
        The package's ``globals()``: a name, once imported, is kept there.

    Examples
    --------
    In a package's ``__init__.py``::

        _LAZY = {"read_mss": "reader", "write_mss": "writer"}
        __getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())
    """

    def __getattr__(name: str) -> Any:
        if name not in lazy:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{lazy[name]}"), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted([*namespace, *lazy])

    return __getattr__, __dir__
