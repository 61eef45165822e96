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
