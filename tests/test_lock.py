"""requirements.lock, from which `make` builds .venv, pins every requirement pyproject.toml declares
(issue 46): a range added or changed without `make lock` fails here, naming the package."""

import re
import tomllib
from pathlib import Path

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]
#: The extras the lock covers (Makefile: LOCK_EXTRAS).
LOCKED_EXTRAS = ("dev", "dask", "formats", "browser", "docs")


def _pins(text: str) -> dict[str, list[str]]:
    """``{name: [version, ...]}`` of the lock's ``name==version`` lines (a package may be pinned once
    per Python version range)."""
    pins: dict[str, list[str]] = {}
    for name, version in re.findall(r"^([A-Za-z0-9][A-Za-z0-9_.\-]*)==([^\s;\\]+)", text, re.M):
        pins.setdefault(canonicalize_name(name), []).append(version)
    return pins


def _declared() -> list[Requirement]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    reqs = [*project["dependencies"], *(r for e in LOCKED_EXTRAS for r in project["optional-dependencies"][e])]
    return [r for r in map(Requirement, reqs) if canonicalize_name(r.name) != "tyrelab"]


def _missing(text: str) -> list[str]:
    pins, out = _pins(text), []
    for req in _declared():
        versions = pins.get(canonicalize_name(req.name), [])
        if not versions:
            out.append(f"{req.name}: not in requirements.lock")
        elif not any(req.specifier.contains(v, prereleases=True) for v in versions):
            out.append(f"{req.name}: requirements.lock pins {', '.join(versions)}, outside {req.specifier}")
    return out


def test_the_lock_pins_every_declared_requirement():
    text = (ROOT / "requirements.lock").read_text()
    missing = _missing(text)
    assert not missing, "run `make lock` (pyproject.toml changed): " + "; ".join(missing)
    assert "--hash=sha256:" in text  # installed with --require-hashes


def test_a_requirement_the_lock_lacks_is_named():
    text = "numpy==1.0.0 \\\n    --hash=sha256:00\n"
    missing = _missing(text)
    assert "numpy: requirements.lock pins 1.0.0, outside >=1.26" in missing
    assert any(m.startswith("scipy: not in") for m in missing)
