"""Every ```python snippet of docs/python.md runs, in order, in one namespace, in a scratch
directory that links the source tree's tests/ and examples/ (the files the snippets read)."""
import os
import re

import matplotlib

matplotlib.use("Agg")

from conftest import SOURCE  # noqa: E402


def snippets():
    with open(os.path.join(SOURCE, "docs", "python.md")) as f:
        text = f.read()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_docs_snippets_run(tmp_path, monkeypatch, capsys):
    for d in ("tests", "examples"):
        os.symlink(os.path.join(SOURCE, d), tmp_path / d)
    monkeypatch.chdir(tmp_path)
    blocks = snippets()
    assert len(blocks) >= 10
    namespace = {"__name__": "docs_python"}
    for i, code in enumerate(blocks):
        try:
            exec(compile(code, f"docs/python.md snippet {i + 1}", "exec"), namespace)
        except Exception as e:  # name the snippet that failed
            raise AssertionError(f"docs/python.md snippet {i + 1} failed: {e!r}\n{code}") from e
    out = capsys.readouterr().out
    assert "did you mean: yoshida-6" in out
    assert "raised by the right-hand side f(t, y) at t = 1.125" in out
    assert "True 1.4" in out                      # the heavy top from callables, bitwise
    assert "[0.70706996 1.11775851]" in out       # harminv of the Yee cavity
    assert "[0.70678361]" in out                  # harminv of mesh Maxwell's TE11
    for png in ("energy.png", "orbit.png", "ez.png", "wp.png"):
        assert (tmp_path / png).stat().st_size > 10000


def test_readme_python_snippet_runs():
    with open(os.path.join(SOURCE, "README.md")) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), flags=re.S)
    assert len(blocks) == 1
    namespace = {}
    exec(compile(blocks[0], "README.md python snippet", "exec"), namespace)
    assert namespace["r"].q.shape == (1001, 2)
