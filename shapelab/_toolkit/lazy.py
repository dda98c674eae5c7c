"""One lazy re-export helper for the packages of shapelab.

``shapelab``, ``shapelab.plot``, ``shapelab.widgets`` and ``shapelab.check`` list
their public names and the submodule that defines each; a name is imported on first
access (PEP 562 module ``__getattr__``), so that ``import shapelab`` stays fast and
a notebook only pays for the modules it uses.  (The Scientific Python
``lazy_loader`` package does the same; it is not a dependency of shapelab.)
"""

from __future__ import annotations

import importlib

__all__ = ["attach"]


def attach(package: str, exports: dict, submodules=(), eager=()):
    """Return ``(__getattr__, __dir__)`` for the package named ``package``.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : dict
        ``{public name: submodule}``: ``package.name`` is
        ``package.submodule.name``, imported on first access and then cached in the
        package's namespace.
    submodules : iterable of str
        Submodules reachable as attributes (``shapelab.plot``), imported on access.
    eager : iterable of str
        Names the package defines itself, listed by ``dir()``.
    """
    exports = dict(exports)
    submodules = frozenset(submodules)
    namespace = importlib.import_module(package).__dict__

    def __getattr__(name: str):
        if name in exports:
            module = importlib.import_module(f"{package}.{exports[name]}")
            value = getattr(module, name)
            namespace[name] = value
            return value
        if name in submodules:
            return importlib.import_module(f"{package}.{name}")
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(namespace) | set(exports) | submodules | set(eager))

    return __getattr__, __dir__
