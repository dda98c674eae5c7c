"""One lazy re-export helper for the packages of shapelab.

``shapelab``, ``shapelab.plot``, ``shapelab.widgets`` and ``shapelab.check`` list
their public names and the submodule that defines each; a name is imported on first
access (PEP 562 module ``__getattr__``), so that ``import shapelab`` stays fast and
a notebook only pays for the modules it uses.  (The Scientific Python
``lazy_loader`` package does the same; it is not a dependency of shapelab.)
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import types

__all__ = ["attach", "moved"]


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
    module = importlib.import_module(package)
    namespace = module.__dict__
    namespace["_lazy_names"] = frozenset(exports)
    module.__class__ = _Package

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


class _Package(types.ModuleType):
    """A package whose public names win over its submodules of the same name.

    ``shapelab.hausdorff`` is the function, defined in the module ``shapelab.hausdorff``
    (likewise ``icp`` and ``report``).  Importing a submodule binds it as an attribute of its package;
    here that binding is skipped when the name is one of the package's lazy exports,
    so ``shapelab.hausdorff`` stays the function after ``from shapelab.hausdorff import
    directed_hausdorff``.  (``import shapelab.hausdorff as m`` gives the function too:
    write ``from shapelab import ...`` or ``importlib.import_module`` for the module.)
    """

    def __setattr__(self, name, value):
        if isinstance(value, types.ModuleType) and name in self.__dict__.get("_lazy_names", ()):
            return
        super().__setattr__(name, value)


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports a module that moved under its old dotted name (the same module object)."""

    def __init__(self, package: str, moves: dict):
        self.moves = {f"{package}.{old}": f"{package}.{new}" for old, new in moves.items()}

    def target(self, fullname: str):
        for old, new in self.moves.items():
            if fullname == old or fullname.startswith(old + "."):
                return new + fullname[len(old) :]
        return None

    def find_spec(self, fullname, path=None, target=None):
        new = self.target(fullname)
        if new is None:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        module = importlib.import_module(self.target(spec.name))
        spec.loader_state = module.__spec__  # the import system overwrites __spec__
        return module

    def exec_module(self, module):
        module.__spec__ = module.__spec__.loader_state

    def get_code(self, fullname):
        """What ``python -m OLD`` runs: the moved module as ``python -m NEW`` runs it."""
        new = self.target(fullname)
        source = f"import runpy\nrunpy.run_module({new!r}, run_name='__main__', alter_sys=True)\n"
        return compile(source, f"<{fullname}, moved to {new}>", "exec")


def moved(package: str, moves: dict) -> None:
    """Keep old import paths of ``package``'s moved modules working.

    ``moved("shapelab", {"power": "triangulation"})`` makes ``import shapelab.power``
    (and ``from shapelab.power import x``) give the module ``shapelab.triangulation``
    itself, and ``python -m shapelab.power`` run it, so that code written against an
    earlier layout keeps running; the file tree shows only the new layout.
    """
    for finder in sys.meta_path:
        if isinstance(finder, _Alias):
            finder.moves.update(_Alias(package, moves).moves)
            return
    sys.meta_path.insert(0, _Alias(package, moves))
