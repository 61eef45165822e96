import pytest


@pytest.fixture(scope="session")
def small_report(full_report):
    """The tiny campaign's report, built through every stage (``full_report`` in tests/conftest.py)."""
    return full_report
