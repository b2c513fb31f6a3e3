"""The example scripts run end to end (their --quick variants: a small model and a short drive)."""

import os
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def run_example(name, *args):
    pytest.importorskip("scipy")
    pytest.importorskip("matplotlib")
    result = subprocess.run([sys.executable, str(SOURCE_DIR / "examples" / name), "--quick", *args],
                            cwd=SOURCE_DIR, capture_output=True, text=True, env=os.environ.copy())
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def test_screen_and_optimize():
    out = run_example("screen_and_optimize.py", "--limit", "120")
    assert "SLSQP: Optimization terminated successfully" in out
    assert "full order at the optimum" in out


def test_tolerance_uq(tmp_path):
    out = run_example("tolerance_uq.py", "--out", str(tmp_path))
    assert "mastrom uq: " in out or (tmp_path / "uq.h5").exists()
    assert (tmp_path / "peak_relative_acceleration.png").stat().st_size > 10_000
    assert (tmp_path / "uq.csv").read_text().startswith("kind,name,statistic,estimate,lower,upper")
