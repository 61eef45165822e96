"""The sixth hostile round, raw runs (issue 46, Deliver 4): a sample a converted channel (float32)
cannot hold is refused with one line naming the channel and row, not turned into infinity with a
floating-point note on stderr."""

import pytest

from tests.synthetic import spring_damper_recording
from tyrelab.rawformat import RunFileError, check_run


@pytest.mark.parametrize("scale", [1e300, -1e39])
def test_a_sample_beyond_float32_is_refused_naming_channel_and_row(scale):
    df = spring_damper_recording(duration_s=20)
    df.loc[7, "load_beam_2_N"] = scale
    with pytest.raises(RunFileError, match=r"^channel load_beam_2_N has a sample of -?1e\+(300|39) at row 7, beyond "
                                           r"the 3\.4e\+38 a float32 channel holds"):
        check_run(df, 0.0)


def test_large_but_representable_samples_pass_that_check():
    df = spring_damper_recording(duration_s=20)
    df["time_s"] = df["time_s"] + 1e39  # the time base is stored as float64: not this check's
    try:
        check_run(df, 0.0)
    except RunFileError as exc:
        assert "float32" not in str(exc)
