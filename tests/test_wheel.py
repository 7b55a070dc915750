"""The built wheel is complete: installed in a fresh virtual environment (with its declared
dependencies only, away from the clone), it runs the main job on a built-in engine, lists
every preset and carries the web application's stylesheet."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: hang guard [s] for building the wheel and for installing it with its dependencies
GUARD = 900


def _run(args: list[str], cwd: Path, clone: bool = False) -> subprocess.CompletedProcess[str]:
    """Run ``args``; ``clone``: with this clone's code first on the path, else without it."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTEST_CURRENT_TEST")}
    if clone:
        env["PYTHONPATH"] = str(ROOT / "src")
    result = subprocess.run(
        args,
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=GUARD,
        stdin=subprocess.DEVNULL,
    )
    assert result.returncode == 0, f"{args}:\n{result.stdout[-2000:]}\n{result.stderr[-3000:]}"
    return result


def test_wheel_in_a_fresh_environment_runs_the_main_job(tmp_path: Path) -> None:
    try:  # the build backend, built without isolation (the test extra has it)
        import setuptools
    except ImportError:
        pytest.skip("setuptools is not installed: the wheel cannot be built here")
    if tuple(int(p) for p in setuptools.__version__.split(".")[:2]) < (70, 1):
        pytest.skip(f"setuptools {setuptools.__version__} has no bdist_wheel of its own")

    # a copy of what the sdist holds, so that the build writes nothing into the clone
    source = tmp_path / "source"
    source.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, source / name)
    skip = shutil.ignore_patterns("__pycache__", "*.egg-info", "*.pyc")
    shutil.copytree(ROOT / "src", source / "src", ignore=skip)
    wheels = tmp_path / "wheels"
    _run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q"]
        + ["-w", str(wheels), str(source)],
        tmp_path,
    )
    (wheel,) = wheels.glob("crankbalance-*.whl")

    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    _run([str(python), "-m", "pip", "install", "-q", str(wheel)], tmp_path)

    away = tmp_path / "elsewhere"  # not the clone: only the installed wheel can be imported
    away.mkdir()
    where = _run([str(python), "-c", "import crankbalance; print(crankbalance.__file__)"], away)
    assert str(env_dir) in where.stdout, where.stdout
    analysis = _run([str(env_dir / "bin" / "crankbalance"), "analyze", "paper-inline3"], away)
    from_clone = _run(
        [sys.executable, "-m", "crankbalance", "analyze", "paper-inline3"], away, True
    )
    assert analysis.stdout == from_clone.stdout and "order" in analysis.stdout
    presets = _run([str(env_dir / "bin" / "crankbalance"), "presets", "--format", "json"], away)
    shipped = sorted(p.stem for p in (ROOT / "src" / "crankbalance" / "presets").glob("*.toml"))
    assert all(name in presets.stdout for name in shipped)
    data = "import importlib.resources as r; f = r.files('crankbalance'); "
    data += "print((f / 'web' / 'static' / 'tailwind.css').is_file(), (f / 'py.typed').is_file())"
    assert _run([str(python), "-c", data], away).stdout.split() == ["True", "True"]
