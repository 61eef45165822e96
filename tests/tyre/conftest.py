import pytest

from tyre_synthetic import make_results


@pytest.fixture
def results():
    return make_results()
