"""tyrelab as a package: __all__ everywhere, re-exported by the subpackages, lazily."""

import importlib
import pkgutil

import pytest

import tyrelab
from tyrelab import _lazy

REEXPORTING = ["tyrelab.measurement", "tyrelab.tyre", "tyrelab.vehicle", "tyrelab.rig"]


def all_modules():
    return sorted(m.name for m in pkgutil.walk_packages(tyrelab.__path__, "tyrelab.")
                  if not m.ispkg and not m.name.rsplit(".", 1)[-1].startswith("_"))


@pytest.mark.parametrize("name", all_modules())
def test_every_public_module_declares_all_and_it_is_true(name):
    module = importlib.import_module(name)
    assert isinstance(getattr(module, "__all__", None), list), f"{name} has no __all__"
    missing = [n for n in module.__all__ if not hasattr(module, n)]
    assert not missing, f"{name}.__all__ names missing objects: {missing}"
    assert _lazy.module_all(name) == module.__all__  # the literal the packages read


@pytest.mark.parametrize("package", REEXPORTING)
def test_package_reexports_every_submodule_name(package):
    pkg = importlib.import_module(package)
    ambiguous = set(_lazy.collisions(package))
    for sub in _lazy.submodule_names(package):
        module = importlib.import_module(f"{package}.{sub}")
        assert sub in pkg.__all__
        assert not ambiguous & set(pkg.__all__)  # a name two submodules export is not guessed
        # a sub-package's own submodules (vehicle/solvers/beam) are its names, not the package's
        own = set(_lazy.submodule_names(module.__name__)) if hasattr(module, "__path__") else set()
        for name in set(module.__all__) - set(_lazy.submodule_names(package)) - ambiguous - own:
            assert name in pkg.__all__ and getattr(pkg, name) is getattr(module, name), f"{package}.{name}"
    with pytest.raises(AttributeError, match="no attribute"):
        getattr(pkg, "not_a_name")


def test_collisions_are_reported(tmp_path, monkeypatch):
    pkg = tmp_path / "twins"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text('__all__ = ["f", "g"]\n')
    (pkg / "b.py").write_text('__all__: list[str] = ["f"]\n')
    (pkg / "_private.py").write_text('__all__ = ["f"]\n')
    monkeypatch.syspath_prepend(str(tmp_path))
    assert _lazy.collisions("twins") == {"f": ["a", "b"]}
    getattr_, dir_ = _lazy.attach("twins")
    assert getattr_("__all__") == ["a", "b", "g"] and dir_() == getattr_("__all__")  # f is ambiguous: not re-exported


def test_top_level_names_resolve_to_their_homes():
    from tyrelab.measurement import apparent_mass
    from tyrelab import api, rawformat

    assert tyrelab.analyze_recording is api.analyze_recording
    assert tyrelab.tyre_force is apparent_mass.tyre_force
    assert tyrelab.RunFileError is rawformat.RunFileError
    assert tyrelab.measurement is importlib.import_module("tyrelab.measurement")
    assert set(dir(tyrelab)) >= {"analyze_recording", "warehouse", "resources"}
