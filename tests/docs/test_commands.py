"""Every command the README and the user guide (docs/guide/*.md) show runs as written.

Each page's ```sh and ```python blocks run in order, in a scratch folder of their own that has the
repository's examples/ and scripts/, build/curvemesh, `curvemesh` on the PATH and the build's
Python module importable: a later block may use what an earlier one wrote, as a reader would. A
block is left out only when the line right before it says why, `<!-- not-run: REASON -->` with one
of the REASONS below (and the README's `<!-- test-command -->` block, which is CI's own command).

The environment (ctest sets it): CURVEMESH_EXE, the curvemesh executable; CURVEMESH_PYTHONPATH,
the folder that holds the build's `curvemesh` package.
"""
import os
import pathlib
import re
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
PAGES = [REPO / "README.md", *sorted((REPO / "docs" / "guide").glob("*.md"))]
REASONS = {
    "sets up the machine",
    "builds the project",
    "needs the openclipart collection",
    "needs a Slurm cluster",
    "runs for minutes",
}
NOT_RUN = re.compile(r"<!--\s*not-run:\s*(.*?)\s*-->")
FENCE = re.compile(r"^```(\w*)\s*$")


def blocks(path):
    """(line, language, code, reason) of every fenced block of a page; reason is why it is not run
    (None when it runs)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    found, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        start, language = i, m.group(1)
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        before = next((lines[k].strip() for k in range(start - 1, -1, -1) if lines[k].strip()), "")
        marker = NOT_RUN.search(before)
        reason = marker.group(1) if marker else ("CI's test command" if before == "<!-- test-command -->" else None)
        found.append((start + 1, language, "\n".join(lines[start + 1:j]), reason))
        i = j + 1
    return found


def runnable(path):
    return [(line, language, code) for line, language, code, reason in blocks(path)
            if language in ("sh", "python") and reason is None]


@pytest.fixture(scope="module")
def exe():
    path = pathlib.Path(os.environ.get("CURVEMESH_EXE", REPO / "build" / "curvemesh")).resolve()
    if not path.is_file():
        pytest.fail(f"the curvemesh executable {path} is missing (set CURVEMESH_EXE)")
    return path


def scratch(tmp_path, exe):
    """A folder laid out as the repository's top folder is for a reader, and the environment."""
    for name in ("examples", "scripts"):
        os.symlink(REPO / name, tmp_path / name)
    (tmp_path / "build").mkdir()
    os.symlink(exe, tmp_path / "build" / "curvemesh")
    env = dict(os.environ, PATH=f"{tmp_path / 'build'}{os.pathsep}{os.environ.get('PATH', '')}",
               PYTHONDONTWRITEBYTECODE="1")
    module = os.environ.get("CURVEMESH_PYTHONPATH")
    if module:
        env["PYTHONPATH"] = str(pathlib.Path(module).resolve())
    return env


@pytest.mark.parametrize("page", PAGES, ids=[p.relative_to(REPO).as_posix() for p in PAGES])
def test_every_command_of_the_page_runs(page, exe, tmp_path):
    todo = runnable(page)
    shown = [b for b in blocks(page) if b[1] in ("sh", "python")]
    assert todo or all(reason for *_, reason in shown), f"{page.name}: no block found to run"
    if not todo:
        pytest.skip(f"every command of {page.name} is marked not-run")
    env = scratch(tmp_path, exe)
    for line, language, code in todo:
        if language == "python" and "PYTHONPATH" not in env:
            pytest.fail("CURVEMESH_PYTHONPATH is not set: the page's Python cannot import curvemesh")
        command = ["bash", "-euo", "pipefail", "-c", code] if language == "sh" else ["/usr/bin/python3", "-c", code]
        r = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        where = f"{page.relative_to(REPO)}, the {language} block at line {line}"
        assert r.returncode == 0, f"{where} failed (exit {r.returncode}):\n{code}\n--- stderr:\n{r.stderr}"
        print(f"ran {where}")


def test_most_commands_run():
    ran = sum(len(runnable(page)) for page in PAGES)
    left_out = sum(1 for page in PAGES for *_, reason in blocks(page) if reason)
    assert ran >= 15 and ran > 2 * left_out, f"{ran} blocks run, {left_out} left out"


def test_blocks_not_run_say_why_in_known_words():
    for page in PAGES:
        for line, language, code, reason in blocks(page):
            if reason is not None and reason != "CI's test command":
                assert reason in REASONS, f"{page.name}:{line}: not-run reason {reason!r} is none of {sorted(REASONS)}"
    # The set left out stays small and explicit: the set-up commands, the cluster, the collection.
    left_out = [(page.name, line) for page in PAGES for line, _, _, reason in blocks(page) if reason]
    assert len(left_out) <= 8, f"{len(left_out)} blocks are not run: {left_out}"


def test_a_marker_leaves_out_only_the_block_right_after_it(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("<!-- not-run: needs a Slurm cluster -->\n```sh\nsbatch x\n```\n\ntext\n\n```sh\ncurvemesh x\n```\n")
    assert [(language, code) for _, language, code in runnable(page)] == [("sh", "curvemesh x")]


def test_the_readmes_test_command_is_what_ci_runs():
    """.ci/run takes the first fenced block after `<!-- test-command -->`: it must be set-up command
    (2), install, build and the whole test suite."""
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    program = re.search(r"awk '([^']*)' README.md", ci)
    assert program, ".ci/run no longer reads README.md with awk: update this test"
    r = subprocess.run(["awk", program.group(1), "README.md"], cwd=REPO, capture_output=True, text=True, check=True)
    command = r.stdout.strip()
    assert command.startswith("scripts/install-deps.sh && cmake -S . -B build"), command
    assert "cmake --build build" in command and "ctest --test-dir build" in command, command
    assert "\n" not in command, "the test command is one line"


def test_the_readmes_first_set_up_command_meshes_a_bundled_drawing():
    readme = REPO / "README.md"
    setup = [code for _, language, code, reason in blocks(readme) if reason == "sets up the machine"]
    assert setup and "scripts/install-deps.sh" in setup[0] and "build/curvemesh mesh examples/" in setup[0], setup
