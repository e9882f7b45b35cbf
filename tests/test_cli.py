"""The command line: one scene in Pi-groups or physical units, records, fits, histories and plots."""

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import isoslide
from isoslide.cli import main
from isoslide.store.history_io import read_history
from test_records import DAMAGE  # tests/ is on sys.path


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


# ----------------------------------------------------------------------------- records on the command line

PHYSICAL = ["--M-b", "8e5", "--T-b", "2.4", "--xi-b", "0.1", "--m-ec", "800", "--mu-s", "0.25",
            "--mu-k", "0.2"]


def test_solve_physical_with_a_sample_record_defaults_to_the_fitted_scales(capsys):
    """--record without --a-p/--T-p: the fitted Ricker's scales, reported; the result is the
    library's for the record as recorded."""
    assert main(["solve-physical", "--record", "TAK-090", *PHYSICAL, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rec = isoslide.records.sample("Kobe_1995_TAK-090")
    fit = rec.fit()
    scene = isoslide.Scene.from_physical(fit.a_p, fit.T_p, 8e5, 2.4, 0.1, 800.0, 0.25, 0.2, pulse=rec)
    sol = isoslide.solve(scene)
    assert out["u_max_m"] == sol.u_max and out["u_residual_m"] == sol.u_residual
    assert out["fitted_pulse"]["a_p"] == fit.a_p and out["fitted_pulse"]["T_p"] == fit.T_p
    assert out["fitted_pulse"]["polarity"] == -1
    assert out["scene"]["pulse"] == "Kobe_1995_TAK-090" and out["record"]["station"] == "Takatori"


def test_solve_physical_with_given_scales_and_an_at2_file_does_not_fit(capsys, tmp_path, monkeypatch):
    """--record FILE.AT2 with --a-p and --T-p: those scales, no fit, no fitted pulse reported."""
    calls = []
    monkeypatch.setattr(isoslide.records.record, "fit_pulse", lambda *a, **k: calls.append(1))
    at2 = Path(__file__).parent / "data" / "records" / "nga_west2.AT2"
    assert main(["solve-physical", "--record", str(at2), "--a-p", "2", "--T-p", "0.1", *PHYSICAL,
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert calls == [] and "fitted_pulse" not in out
    assert out["scene"]["a_p"] == 2.0 and out["scene"]["T_p"] == 0.1
    assert out["scene"]["pi2"] == pytest.approx(0.2 * 9.80665 / 2.0)


def test_solve_in_pi_groups_with_a_csv_record_reports_the_fit(capsys, tmp_path):
    rec = isoslide.records.sample("PAC-175")
    csv_path = tmp_path / "pac.csv"
    np.savetxt(csv_path, np.column_stack([rec.time, rec.accel]), delimiter=",", header="time,accel",
               comments="")
    assert main(["solve", "--pi2", "0.3", "--pi3", "1", "--pi4", "0.1", "--record", str(csv_path)]) == 0
    text = capsys.readouterr().out
    sol = isoslide.solve(isoslide.Scene(0.3, 1.0, 0.1, pulse=rec))
    assert f"pi1: {sol.pi1}" in text and f"pi1_residual: {sol.pi1_residual}" in text
    assert "fitted pulse: ricker: a_p = 4.92718 m/s^2 (0.5024 g), T_p = 0.470482 s" in text
    assert "polarity -1" in text


@pytest.mark.parametrize("suffix", [".csv", ".h5"])
def test_history_option_writes_the_solved_history(capsys, tmp_path, suffix):
    path = tmp_path / f"h{suffix}"
    assert main(["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--history", str(path),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    table = read_history(path)
    assert out["history_file"] == str(path)
    assert table.units["slide_disp"] == "m" and table.attrs["u_max"] == out["u_max_m"]
    assert np.max(np.abs(table.columns["slide_disp"])) == pytest.approx(out["u_max_m"], rel=1e-9)


def test_a_planar_history_holds_both_components_and_plots_the_path(capsys, tmp_path):
    """In the plane the history file has every motion along x and y: the largest ``|u|`` of its rows is the
    peak slide, in the direction reported; the plot draws it."""
    path, plot = tmp_path / "h.h5", tmp_path / "p.png"
    assert main(["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--pulse-y", "antisymmetric_ricker",
                 "--a-py", "4", "--history", str(path), "--plot", str(plot), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    c = read_history(path).columns
    size = np.hypot(c["slide_disp_x"], c["slide_disp_y"])
    k = int(np.argmax(size))
    assert out["contact"] == "plane"
    assert size[k] == pytest.approx(out["u_max_m"], rel=1e-9)
    assert math.atan2(c["slide_disp_y"][k], c["slide_disp_x"][k]) == pytest.approx(out["peak_angle"], abs=1e-9)
    assert plot.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("suffix, magic", [(".png", b"\x89PNG"), (".pdf", b"%PDF")])
def test_plot_option_writes_png_or_pdf(capsys, tmp_path, suffix, magic):
    path = tmp_path / f"p{suffix}"
    assert main(["solve", "--pi2", "0.2", "--pi3", "1", "--pi4", "0.1", "--plot", str(path)]) == 0
    assert f"plot_file: {path}" in capsys.readouterr().out
    assert path.read_bytes()[:4] == magic and path.stat().st_size > 10_000


def test_fit_command_prints_and_plots_the_fitted_pulse(capsys, tmp_path):
    assert main(["fit", "Kobe_1995_TAK-090", "--shape", "mp", "--json", "--plot", str(tmp_path / "f.png")]) == 0
    out = json.loads(capsys.readouterr().out)
    fit = isoslide.records.sample("Kobe_1995_TAK-090").fit("mp")
    assert out["fitted_pulse"]["shape"] == "mavroeidis_papageorgiou"
    assert out["fitted_pulse"]["T_p"] == fit.T_p and out["fitted_pulse"]["gamma"] == fit.shape_params["gamma"]
    assert (tmp_path / "f.png").read_bytes()[:4] == b"\x89PNG"
    assert main(["fit", "TAK-090"]) == 0
    text = capsys.readouterr().out
    assert "fitted ricker: a_p = 4.82343 m/s^2 (0.4919 g), T_p = 1.56095 s" in text


def test_records_command_lists_the_suites(capsys):
    assert main(["records", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in rows] == list(isoslide.records.suites())
    assert main(["records"]) == 0
    text = capsys.readouterr().out
    assert all(name in text for name in isoslide.records.suites())


def test_records_command_lists_the_pyslammer_samples_with_event_station_and_licence(capsys):
    assert main(["records", "pyslammer", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in rows] == list(isoslide.records.samples())
    kobe = next(r for r in rows if r["name"] == "Kobe_1995_TAK-090")
    assert kobe["event"] == "Kobe, Japan 1995" and kobe["station"] == "Takatori" and kobe["pulse"] is True
    assert list(kobe["components"]) == ["x"]
    assert all("GPL-3.0-only" in r["licence"] for r in rows)
    assert main(["records", "pyslammer"]) == 0
    text = capsys.readouterr().out
    assert len(text.splitlines()) == len(rows) + 2 and "licence: pyslammer" in text


def test_records_command_lists_a_fema_suite_with_dt_npts_pga_and_pulse(capsys):
    """Each row: name, components, dt, npts, PGA and the pulse flag, as the library's suite has them."""
    assert main(["records", "fema-p695-near-field-pulse"]) == 0
    lines = capsys.readouterr().out.splitlines()
    motions = isoslide.records.suite("fema-p695-near-field-pulse")
    assert len(lines) == 1 + len(motions) + 1 and lines[-1].startswith("licence: fema-p695")
    for line, gm in zip(lines[1:], motions, strict=False):
        name, comps, dt, npts, pga, pulse = line.split()[:6]
        assert (name, comps, float(dt), pulse) == (gm.name, "xy", gm.x.dt, "yes")
        assert npts.split("/") == [str(n) for n in sorted({gm.x.npts, gm.y.npts})]
        assert float(pga) == pytest.approx(gm.pga, abs=5e-4)


def test_records_command_reads_a_folder_of_at2_pairs(capsys, tmp_path):
    at2 = (Path(__file__).parent / "data" / "records" / "nga_west2.AT2").read_text()
    for suffix in ("000", "090", "-UP"):
        (tmp_path / f"RSN1_TEST_STA{suffix}.AT2").write_text(at2)
    assert main(["records", str(tmp_path), "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["name"] == "RSN1_TEST_STA" and list(row["components"]) == ["x", "y", "z"]
    assert row["components"]["y"]["npts"] == 23 and row["dt"] == 0.01


def test_records_command_refuses_a_damaged_pair_in_one_line_naming_the_file(tmp_path):
    """The installed script, a folder whose y component has a value of 1e308: exit 2, no traceback."""
    at2 = (Path(__file__).parent / "data" / "records" / "nga_west2.AT2").read_text()
    (tmp_path / "RSN1_TEST_STA000.AT2").write_text(at2)
    (tmp_path / "RSN1_TEST_STA090.AT2").write_text(at2.replace("3.7148559E-02", "1.0E+308"))
    script = Path(sys.executable).parent / "isoslide"
    if not script.exists():
        script = shutil.which("isoslide")
    r = subprocess.run([str(script), "records", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stderr.count("\n") == 1
    assert "RSN1_TEST_STA090.AT2, line 5:" in r.stderr and "100 g" in r.stderr and "1e+308" in r.stderr


@pytest.mark.parametrize("command", ["fit", "records"])
def test_every_damaged_record_file_gives_a_result_or_one_line_naming_it(capsys, tmp_path, command):
    """Each kind of damage of tests/test_records.py, through ``isoslide fit FILE`` and ``isoslide
    records FOLDER`` (the damaged file as the y component of a pair): exit 0, or exit 2 with one
    line that names the file (an exception other than ValueError would escape main)."""
    source = Path(__file__).parent / "data" / "records" / "nga_west2.AT2"
    codes = set()
    for kind, damage in DAMAGE.items():
        folder = tmp_path / kind
        folder.mkdir()
        out = damage(source.read_text())
        bad = folder / ("RSN1_TEST_STA090.AT2" if command == "records" else "damaged.AT2")
        bad.write_bytes(out if isinstance(out, bytes) else out.encode("utf-8"))
        if command == "records":
            (folder / "RSN1_TEST_STA000.AT2").write_text(source.read_text())
        code = main([command, str(folder if command == "records" else bad)])
        err = capsys.readouterr().err
        assert code in (0, 2), kind
        if code == 2:
            assert err.count("\n") == 1 and err.startswith("isoslide: error: ") and bad.name in err, (kind, err)
        codes.add(code)
    assert codes == {0, 2}


@pytest.mark.parametrize("args, words", [
    (["solve", "--pi2", "abc", "--pi3", "1"], "argument --pi2: invalid float value: 'abc'"),
    (["solve", "--pi2", "nan", "--pi3", "1"], "pi2 = nan is invalid; allowed: a finite number"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "no-such-record"],
     "record = 'no-such-record' is not a .at2/.csv file or a bundled sample"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "missing.AT2"], "record = 'missing.AT2': no such file"),
    (["fit", "{bad_at2}"], "line 7: expected 23 values"),
    (["fit", "{binary_csv}"], "not a text file"),
    (["fit", "TAK-090", "--shape", "cosine"], "argument --shape: invalid choice: 'cosine'"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--history", "h.txt"], "history = 'h.txt' has an unknown extension"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--plot", "p.jpg"], "plot = 'p.jpg' has an unknown extension"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--history", "/no/such/dir/h.csv"], "history = '/no/such/dir/h.csv'"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "TAK-090", "--pulse", "ricker"],
     "pulse = 'ricker' and record = 'TAK-090' exclude each other"),
    (["solve-physical", *PHYSICAL], "the following arguments are required: --a-p, --T-p"),
    (["solve-physical", "--record", "TAK-090", "--a-p", "-3", *PHYSICAL], "a_p = -3.0 is out of range"),
    (["records", "no-such-suite"], "suite = 'no-such-suite' is invalid; allowed: one of fema-p695-far-field"),
    (["records", "/no/such/folder"], "suite = '/no/such/folder': no such folder or file"),
    (["records", "{bad_manifest}"], "m.csv, line 1: expected a header naming the columns name, x, y"),
    (["fit", "{huge_csv}"], "huge.csv, line 3: expected a finite acceleration within |a| <= 100 g"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--pulse-y", "cosine"], "argument --pulse-y: invalid choice: 'cosine'"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--pulse-y", "ricker", "--angle", "abc"],
     "argument --angle: invalid float value: 'abc'"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--pulse-y", "ricker", "--angle", "100"],
     "angle = 100.0 is out of range"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--angle", "nan"], "angle = nan is invalid; allowed: a finite number"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--pulse-y", "ricker", "--pi15", "0"], "pi15 = 0.0 is out of range"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--pi14", "0.5"],
     "pi14 = 0.5 shapes a second horizontal component, and there is none"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record-y", "PAC-175"], "record_y = 'PAC-175' without --record"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "TAK-090", "--record-y", "nope"],
     "record_y = 'nope' is not a .at2/.csv file or a bundled sample"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "TAK-090", "--record-y", "missing.AT2"],
     "record_y = 'missing.AT2': no such file"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "TAK-090", "--record-y", "{huge_csv}"],
     "huge.csv, line 3: expected a finite acceleration"),
    (["solve", "--pi2", "0.2", "--pi3", "1", "--record", "TAK-090", "--record-y", "PAC-175", "--pulse-y", "ricker"],
     "pulse_y = 'ricker' and record_y = 'PAC-175' exclude each other"),
    (["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--a-py", "3"],
     "a_py = 3.0 shapes a second horizontal component, and there is none"),
    (["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--pulse-y", "ricker", "--a-py", "-3"],
     "a_py = -3.0 is out of range"),
    (["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--pulse-y", "ricker", "--T-py", "0"],
     "T_py = 0.0 is out of range"),
    (["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--pulse-y", "ricker", "--t-y", "x"],
     "argument --t-y: invalid float value: 'x'"),
])
def test_bad_input_gives_one_line_naming_parameter_and_value_exit_2(capsys, tmp_path, args, words):
    bad_at2 = Path(__file__).parent / "data" / "records" / "truncated.AT2"
    binary_csv = tmp_path / "binary.csv"
    binary_csv.write_bytes(b"\xff\xfe\x00\x81" * 50)
    bad_manifest = tmp_path / "m.csv"
    bad_manifest.write_text("nmae,x,y\n")
    huge_csv = tmp_path / "huge.csv"
    huge_csv.write_text("0.0,0.1\n0.01,0.2\n0.02,1e308\n0.03,0.0\n")
    args = [a.format(bad_at2=bad_at2, binary_csv=binary_csv, bad_manifest=bad_manifest, huge_csv=huge_csv)
            for a in args]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("isoslide: error: ") and words in err, err


def test_console_script_solves_a_record_and_reports_bad_input(tmp_path):
    """The installed ``isoslide`` script: a record scene with a history file, then a bad sample (exit 2)."""
    script = Path(sys.executable).parent / "isoslide"
    if not script.exists():
        script = shutil.which("isoslide")
    h = tmp_path / "kobe.hdf5"
    r = subprocess.run([str(script), "solve-physical", "--record", "TAK-090", *PHYSICAL, "--history", str(h)],
                       capture_output=True, text=True, check=True)
    assert "fitted pulse: ricker" in r.stdout and read_history(h).attrs["pulse"] == "Kobe_1995_TAK-090"
    bad = subprocess.run([str(script), "fit", "nope"], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("isoslide: error: record = 'nope'")


def test_solve_with_vertical_motion_matches_the_library(capsys):
    """--pi17 with --pulse-z is the scene with vertical ground motion; lift-off exits 2 naming pi17."""
    assert main(["solve", "--pi2", "0.2", "--pi3", "1", "--pi4", "0.1", "--pi17", "0.3", "--pulse-z", "ricker",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sol = isoslide.solve(isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi17=0.3, pulse_z="ricker"))
    assert out["pi1"] == sol.pi1 and out["model"] == sol.model == "coulomb+vertical"
    assert out["scene"]["pi17"] == 0.3 and out["scene"]["pulse_z"] == "ricker"
    assert main(["solve", "--pi2", "0.2", "--pi3", "1", "--pi17", "3", "--pulse-z", "ricker"]) == 2
    assert "pi17 = 3.0 lifts the contents off" in capsys.readouterr().err


# ----------------------------------------------------------------------------- planar sliding on the command line

PLANAR = ["--pi2", "0.2", "--pi3", "1", "--pi4", "0.1", "--pulse-y", "antisymmetric_ricker", "--pi14", "0.7",
          "--pi15", "1.2", "--pi16", "0.1", "--angle", "0.5"]


def test_solve_in_the_plane_matches_the_library(capsys):
    """--pulse-y with --pi14/--pi15/--pi16 and --angle: the library's planar scene, its peak and direction."""
    assert main(["solve", *PLANAR, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    scene = isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pulse_y="antisymmetric_ricker", pi14=0.7, pi15=1.2,
                           pi16=0.1, angle=0.5)
    sol = isoslide.solve(scene)
    assert scene.planar and out["scene"]["planar"] is True
    assert out["pi1"] == sol.pi1 and out["pi1_residual"] == sol.pi1_residual
    assert out["peak_angle"] == sol.peak_angle and out["peak_angle_deg"] == pytest.approx(np.degrees(sol.peak_angle))
    assert out["model"] == sol.model and out["model"].endswith("+planar") and out["contact"] == "plane"
    assert out["scene"]["pulse_y"] == "antisymmetric_ricker" and out["scene"]["angle"] == 0.5
    assert (out["scene"]["pi14"], out["scene"]["pi15"], out["scene"]["pi16"]) == (0.7, 1.2, 0.1)
    assert main(["solve", *PLANAR]) == 0
    text = capsys.readouterr().out
    assert f"pi1: {sol.pi1}\n" in text and "model: coulomb+planar" in text and "contact: plane" in text
    assert f"peak_angle: {sol.peak_angle} rad ({np.degrees(sol.peak_angle):.6g} deg)" in text


def test_a_scene_along_one_line_reports_its_direction_or_no_slide(capsys):
    """1-D scenes: the angle along x (0 or pi) in the line contact; a scene that never slides: none (null)."""
    assert main(["solve", "--pi2", "0.2", "--pi3", "1", "--pi4", "0.1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["peak_angle"] in (0.0, np.pi) and out["contact"] == "line" and out["scene"]["planar"] is False
    assert main(["solve", "--pi2", "1.5", "--pi3", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pi1"] == 0.0 and out["peak_angle"] is None and out["peak_angle_deg"] is None
    assert main(["solve", "--pi2", "1.5", "--pi3", "0"]) == 0
    assert "peak_angle: none (no slide)" in capsys.readouterr().out


def test_solve_physical_in_the_plane_matches_the_library(capsys):
    """--a-py/--T-py/--t-y in SI units: the same scene as Scene.from_physical, the peak in metres."""
    assert main(["solve-physical", "--a-p", "6", "--T-p", "1.2", *PHYSICAL, "--pulse-y", "ricker",
                 "--a-py", "3", "--T-py", "0.8", "--t-y", "0.3", "--angle", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    scene = isoslide.Scene.from_physical(6.0, 1.2, 8e5, 2.4, 0.1, 800.0, 0.25, 0.2, pulse_y="ricker", a_py=3.0,
                                         T_py=0.8, t_y=0.3, angle=1.0)
    sol = isoslide.solve(scene)
    assert scene.planar and out["u_max_m"] == sol.u_max and out["peak_angle"] == sol.peak_angle
    assert out["scene"]["pi14"] == 0.5 and out["scene"]["pi15"] == pytest.approx(0.8 / 1.2)
    assert out["scene"]["pi16"] == pytest.approx(0.25) and out["model"].endswith("+planar")


def test_a_recorded_pair_runs_as_recorded_on_the_first_records_scales(capsys):
    """--record with --record-y: the library's recorded pair (both on the --record record's fitted a_p, T_p),
    in Pi-groups and in SI units; both records are reported."""
    x, y = isoslide.records.sample("Kobe_1995_TAK-090"), isoslide.records.sample("Northridge_1994_PAC-175")
    assert main(["solve", "--pi2", "0.2", "--pi3", "2", "--pi4", "0.1", "--record", "TAK-090", "--record-y",
                 "PAC-175", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sol = isoslide.solve(isoslide.Scene(pi2=0.2, pi3=2.0, pi4=0.1, pulse=x, pulse_y=y))
    assert out["pi1"] == sol.pi1 and out["peak_angle"] == sol.peak_angle and out["model"] == sol.model
    assert out["record"]["station"] == "Takatori" and out["record_y"]["name"] == "Northridge_1994_PAC-175"
    assert out["fitted_pulse"]["T_p"] == x.fit().T_p and out["scene"]["planar"] is True
    assert main(["solve-physical", "--record", "TAK-090", "--record-y", "PAC-175", *PHYSICAL, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    fit = x.fit()
    scene = isoslide.Scene.from_physical(fit.a_p, fit.T_p, 8e5, 2.4, 0.1, 800.0, 0.25, 0.2, pulse=x, pulse_y=y)
    sol = isoslide.solve(scene)
    assert out["u_max_m"] == sol.u_max and out["peak_angle"] == sol.peak_angle
    assert main(["solve", "--pi2", "0.2", "--pi3", "2", "--pi4", "0.1", "--record", "TAK-090", "--record-y",
                 "PAC-175"]) == 0
    assert "record_y: Northridge_1994_PAC-175 (Northridge 1994, PAC 175), as recorded" in capsys.readouterr().out
