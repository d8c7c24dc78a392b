# The examples of docs/python.md, run one after the other in one namespace (as a reader would in
# one session), in a temporary directory where scenes/ is the repository's.
import os
import re

import pytest

strahl = pytest.importorskip("strahl")


def examples(path):
    with open(path) as f:
        text = f.read()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_python_md_examples_run(source_dir, tmp_path, monkeypatch, capsys):
    blocks = examples(os.path.join(source_dir, "docs", "python.md"))
    assert len(blocks) >= 8
    os.symlink(os.path.join(source_dir, "scenes"), tmp_path / "scenes")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for i, block in enumerate(blocks):
        exec(compile(block, f"docs/python.md example {i + 1}", "exec"), namespace)
    out = capsys.readouterr().out
    # What the page says they print.
    assert "(180, 320, 3) float32" in out
    assert "(60, 80) (60, 80, 3)" in out
    assert "4 difference 4" in out
    assert "['pair'] 7" in out
    assert "<strahl.Instance of group 0>" in out
    assert "stopped early" in out
    assert "pixel (40, 30) of 80×60 (x from the left, row from the top), sample 0 of its" in out
    assert "bad.yaml:2:47: sphere radius must be positive (got -1)" in out
    assert "bad.yaml 2 47" in out
    assert (tmp_path / "lecture.png").exists() and (tmp_path / "copy.yaml").exists()
    assert (tmp_path / "built.mesh0.obj").exists() and (tmp_path / "built.mesh1.obj").exists()
    assert (tmp_path / "whitted-from-pov.yaml").exists()
