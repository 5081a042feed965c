"""The README's Python example (the code block after the line `<!-- python-example -->`) runs as
it is written, from the repository's top folder, so that it cannot drift from the module."""
import os
import pathlib
import re
import subprocess
import sys

import curvemesh

MARKER = "<!-- python-example -->"


def readme_example(repo):
    text = (repo / "README.md").read_text(encoding="utf-8")
    assert MARKER in text, f"README.md has no {MARKER} line"
    after = text.split(MARKER, 1)[1]
    match = re.match(r"\s*```python\n(.*?)\n```", after, re.S)
    assert match, f"no ```python block right after {MARKER}"
    return match.group(1)


def test_readme_example_runs(repo, tmp_path):
    code = readme_example(repo)
    assert "import curvemesh" in code
    # The top folder as the example sees it: the bundled drawings, and room for the files it writes.
    os.symlink(repo / "examples", tmp_path / "examples")
    # The module under test, wherever PYTHONPATH had it (a relative entry would not do from there).
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(curvemesh.__file__).resolve().parents[1]))
    result = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip(), "the example prints nothing"
    written = [p for p in tmp_path.iterdir() if p.name != "examples"]
    assert written, "the example writes no file"
    for path in written:
        assert path.stat().st_size > 0, path
