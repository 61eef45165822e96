import pytest

from tests.tyre.tyre_synthetic import make_results


@pytest.fixture
def results():
    return make_results()


@pytest.fixture(scope="session")
def thesis_model():
    """The thesis' stiffness model (published Tables II, III, VI; issue 27)."""
    from tyrelab.published import thesis_stiffness_model

    return thesis_stiffness_model()
