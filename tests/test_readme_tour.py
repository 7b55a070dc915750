"""The README as a new user reads it: every command of its tour runs as written (in a scratch
folder beside a copy of ``examples/``, like the README's ``tour/``), but those whose comment
marks them ``long``; ``crankbalance web`` prints its URL and then says it is ready; the two
set-up commands are the ones ``.ci/run`` runs, step by step."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()

#: how long [s] one tour command may run before the test gives up on it (a hang guard)
COMMAND_GUARD = 600


def _block_after(heading: str) -> list[str]:
    """The lines of the first ```bash block after ``heading``."""
    text = README[README.index(heading) :]
    block = text[text.index("```bash\n") + len("```bash\n") :]
    return [line for line in block[: block.index("```")].splitlines() if line.strip()]


def tour_commands() -> list[str]:
    """The tour's ``crankbalance`` commands (its set-up lines, venv and folder, aside)."""
    return [
        line
        for line in _block_after("## A tour of the command line")
        if line.startswith("crankbalance ")
    ]


def _is_long(line: str) -> bool:
    return "# long" in line


def _run_in_scratch(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A scratch folder ``tour`` beside a copy of ``examples/``, and an environment whose
    ``crankbalance`` is this interpreter's, with this clone's code."""
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    tour = tmp_path / "tour"
    tour.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    launcher = bin_dir / "crankbalance"
    launcher.write_text(f'#!/bin/sh\nexec {shlex.quote(sys.executable)} -m crankbalance "$@"\n')
    launcher.chmod(0o755)
    env["PATH"] = f"{bin_dir}{os.pathsep}{env['PATH']}"
    return tour, env


COMMANDS = tour_commands()
RUN = [c for c in COMMANDS if not c.startswith("crankbalance web")]


def test_the_tour_is_found_and_its_long_commands_give_their_time() -> None:
    assert len(COMMANDS) >= 20 and any(c.startswith("crankbalance web") for c in COMMANDS)
    for line in COMMANDS:
        if _is_long(line):
            assert re.search(r"# long: .*\d+ min", line), f"a long command gives its time: {line}"


@pytest.mark.parametrize(
    "command",
    [
        pytest.param(c, marks=pytest.mark.skip(reason="marked long in the README"))
        if _is_long(c)
        else c
        for c in RUN
    ],
    ids=[f"{i:02d}-{' '.join(c.split()[1:3])}" for i, c in enumerate(RUN)],
)
def test_tour_command_runs_as_written(command: str, tmp_path: Path) -> None:
    tour, env = _run_in_scratch(tmp_path)
    result = subprocess.run(
        ["bash", "-c", command],
        cwd=tour,
        env=env,
        capture_output=True,
        text=True,
        timeout=COMMAND_GUARD,
        stdin=subprocess.DEVNULL,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip() or any(tour.iterdir()), "prints something or writes a file"
    assert "Traceback" not in result.stderr
    written = re.findall(r"(?:-o|--output|--plot|>)\s+(\S+\.\w+)", command)
    for name in written:
        assert (tour / name).stat().st_size > 0, f"{name} written in the scratch folder"


def test_web_prints_its_url_and_says_when_it_is_ready(tmp_path: Path) -> None:
    """The tour's ``crankbalance web`` on a free port: its first line names the URL, a later
    one says it is ready, and the URL then answers."""
    pytest.importorskip("nicegui")
    import socket
    import urllib.request

    (command,) = [c for c in COMMANDS if c.startswith("crankbalance web")]
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = int(probe.getsockname()[1])
    tour, env = _run_in_scratch(tmp_path)
    args = shlex.split(command, comments=True) + ["--port", str(port)]
    proc = subprocess.Popen(
        ["bash", "-c", shlex.join(args)],
        cwd=tour,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        stdin=subprocess.DEVNULL,
        start_new_session=True,
    )
    from .conftest import hang_guard

    try:
        with hang_guard(COMMAND_GUARD):
            assert proc.stdout is not None
            first = proc.stdout.readline()
            url = f"http://127.0.0.1:{port}/"
            assert url in first and "starting" in first, first
            lines = [proc.stdout.readline()]
            while lines[-1] and "ready" not in lines[-1]:  # until "ready", or the end of output
                lines.append(proc.stdout.readline())
            assert "ready" in lines[-1] and url in lines[-1], lines
            with urllib.request.urlopen(url + "api/presets", timeout=60) as response:
                assert response.status == 200
    finally:
        os.killpg(proc.pid, 15)
        proc.wait(60)
        if proc.stdout is not None:
            proc.stdout.close()


def _steps(command: str) -> list[str]:
    return [step.strip() for step in command.split("&&")]


def test_ci_runs_the_readmes_test_command_step_by_step() -> None:
    """``.ci/run`` runs each ``&&`` step of the README's second command as one of its lines,
    in the README's order (with lint, type checks and the documentation between)."""
    _first, second = _block_after("# crankbalance")[:2]
    ci = [line.strip() for line in (ROOT / ".ci" / "run").read_text().splitlines()]
    at = -1
    for step in _steps(second):
        assert step in ci, f".ci/run lacks the README's step {step!r}"
        assert ci.index(step) > at, f".ci/run runs {step!r} out of the README's order"
        at = ci.index(step)


def test_the_first_command_ends_with_a_result() -> None:
    """The README's first command installs and then prints an analysis (it does not serve)."""
    first = _block_after("# crankbalance")[0]
    assert "python3 -m venv .venv" in first
    assert _steps(first)[-1] == ".venv/bin/crankbalance analyze paper-inline3"
