"""The README's "Use it as a library" example runs as written (on a recording made here)."""

import re
from pathlib import Path

from tests.synthetic import spring_damper_recording

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_library_example_runs(tmp_path, monkeypatch, capsys):
    text = README.read_text(encoding="utf-8")
    block = re.search(r"## Use it as a library\n.*?```python\n(.*?)```", text, re.S).group(1)
    path = tmp_path / "raw" / "demo" / "runs" / "T4_sweep_006.parquet"
    path.parent.mkdir(parents=True)
    spring_damper_recording(force_noise_N=50).to_parquet(path)
    monkeypatch.chdir(tmp_path)
    exec(compile(block, str(README), "exec"), {})
    out = capsys.readouterr().out
    m = re.search(r"K = ([\d.]+) kN/m, C = ([\d.]+) kN s/m at ([\d.]+) Hz, coherence", out)
    k, c, f = (float(v) for v in m.groups())
    assert abs(k - 250.0) < 1.0 and abs(c - 2.0) < 0.05 and f == 4.0  # the recording's K, C and frequency
    assert "QC ok" in out and "'qc_reasons': []" in out


def test_readme_vehicle_library_example_runs(tmp_path, monkeypatch, capsys):
    """The second block: tyrelab.ride on the shipped scenario, tyrelab.exposure on a demo recording."""
    import shutil

    from tyrelab.generate import write_rides
    from tyrelab.resources import scenarios_dir

    text = README.read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", re.search(r"## Use it as a library\n(.*?)\n## ", text, re.S).group(1), re.S)
    block = next(b for b in blocks if "tyrelab.ride(" in b)
    (tmp_path / "raw" / "scenarios").mkdir(parents=True)
    shutil.copy(scenarios_dir() / "modern_tractor.toml", tmp_path / "raw" / "scenarios")
    write_rides(tmp_path / "raw" / "demo", seed=1991, studies=False)
    monkeypatch.chdir(tmp_path)
    exec(compile(block, str(README), "exec"), {})
    out = capsys.readouterr().out
    assert "a8_axis" in out and "above action value" in out and "bounce" in out and "pitch" in out
    assert re.search(r"^0\.\d+ [xyz] (below|above) action value$", out, re.M)  # day.a8_m_s2, a8_axis, verdict
