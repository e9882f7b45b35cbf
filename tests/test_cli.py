"""The command line: one scene in Pi-groups or physical units."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import isoslide
from isoslide.cli import main


def test_cli_pi_groups_json_matches_python(capsys):
    assert main(["solve", "--pi2", "0.2", "--pi3", "1", "--pi4", "0.1", "--pi5", "0.7",
                 "--pi6", "1000", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sol = isoslide.solve(isoslide.Scene(0.2, 1.0, 0.1, 0.7, 1000.0))
    assert out["pi1"] == sol.pi1 and out["model"] == sol.model and out["settled"] is True
    assert out["scene"]["pi6"] == 1000.0


def test_cli_physical_units_gives_metres(capsys):
    args = ["solve-physical", "--a-p", "6", "--T-p", "1.2", "--M-b", "8e5", "--T-b", "2.4",
            "--xi-b", "0.1", "--m-ec", "800", "--mu-s", "0.25", "--mu-k", "0.2", "--beta", "200",
            "--gamma", "0.05", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["u_max_m"] == pytest.approx(0.22592596746266558, rel=1e-6)


def test_cli_bad_value_names_parameter(capsys):
    assert main(["solve", "--pi2", "0.2", "--pi3", "-1"]) == 2
    assert "pi3 = -1.0 is out of range; allowed range" in capsys.readouterr().err


def test_console_script_installed():
    """The ``isoslide`` entry point installed next to the interpreter runs (not ``python -m``)."""
    script = Path(sys.executable).parent / "isoslide"
    if not script.exists():
        script = shutil.which("isoslide")
    assert script, "the isoslide console script is not installed"
    r = subprocess.run([str(script), "solve", "--pi2", "1.5", "--pi3", "0"],
                       capture_output=True, text=True, check=True)
    assert "pi1: 0.0" in r.stdout and "fixed-base+no-slide" in r.stdout
