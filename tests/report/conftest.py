import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from small_campaign import build_small_report  # noqa: E402


@pytest.fixture(scope="session")
def small_report(tmp_path_factory):
    """Context of a tiny campaign run through every stage but simulate (report included)."""
    return build_small_report(tmp_path_factory.mktemp("small_report"))
