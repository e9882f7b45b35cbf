"""Every paper figure renders from small datasets, deterministically, with its caption."""

import matplotlib

matplotlib.use("Agg")

import copy  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import isoslide.config  # noqa: E402
from isoslide import datasets
from isoslide.reports import figures
from isoslide.studies import sweep  # noqa: E402

CONFIG = {
    "chunk_size": 1000, "reference": {"a_p_T_p": 9.80665}, "defaults": {"pi4": 0.1},
    "pi2": {"start": 0.05, "stop": 1.5, "num": 5},
    "studies": {
        "fig3_newmark": {"figure": 3, "pulse": "rectangular", "fixed": {"pi3": 0.0, "pi4": 0.0}},
        "fig5_pi3": {"figure": 5, "dims": {"pi3": [0.01, 1.0]}},
        "fig5_pi4": {"figure": 5, "dims": {"pi3": [1.0], "pi4": [0.0, 0.1]}},
        "fig6_pi5": {"figure": 6, "dims": {"pi3": [0.5, 1.0], "pi5": [0.5, 1.0]}, "fixed": {"beta": 1000.0}},
        "fig7_pi6": {"figure": 7, "dims": {"beta": [10.0, 1000.0]}, "fixed": {"pi3": 1.0, "pi5": 0.5}},
        "fig7_pi7": {"figure": 7, "dims": {"pi7": [0.0, 2.0]}, "fixed": {"pi3": 1.0}},
        "fig8_pi8": {"figure": 8, "dims": {"pi3": [0.1, 1.0], "pi8": [1e-5, 1.0]}},
    },
}


def fig_settings(**override):
    """The ``figures`` section of the default configuration, with overrides."""
    return {**isoslide.config.defaults()["figures"], **override}


@pytest.fixture(scope="module")
def studies():
    out = {}
    for name, spec in sweep.check_config(isoslide.config.validate(copy.deepcopy(CONFIG))).items():
        grid = sweep.build_grid(spec)
        chunks = [sweep.solve_chunk(spec, k) for k in sweep.spec_chunks(spec)]
        out[name] = datasets.merge_chunks(chunks, grid)
    return out


@pytest.mark.parametrize("name", [f"fig{n}" for n in range(1, 9)])
def test_every_figure_renders_with_caption(tmp_path, studies, name):
    outs = [tmp_path / f"{name}.png", tmp_path / f"{name}.pdf", tmp_path / f"{name}.svg"]
    caption = figures.draw(name, studies, outs, fig_settings(dpi=60))
    assert caption.startswith(f"Fig. {name[3]}.")
    for p in outs:
        assert p.stat().st_size > 1000
    assert figures.read_caption(outs[0]) == caption
    assert b"CreationDate" not in outs[1].read_bytes()


def test_figures_are_deterministic(tmp_path, studies):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    for name, ext in (("fig5", "pdf"), ("fig1", "png")):
        a, b = tmp_path / "a" / f"{name}.{ext}", tmp_path / "b" / f"{name}.{ext}"
        figures.draw(name, studies, [a], fig_settings(dpi=50))
        figures.draw(name, studies, [b], fig_settings(dpi=50))
        assert a.read_bytes() == b.read_bytes()


def test_missing_dataset_and_bad_format_are_clear(tmp_path, studies):
    with pytest.raises(KeyError, match="fig6_pi5"):
        figures.draw("fig6", {}, [tmp_path / "x.png"], fig_settings())
    with pytest.raises(ValueError, match="unsupported figure format"):
        figures.draw("fig2", {}, [tmp_path / "x.jpg"], fig_settings())
    with pytest.raises(ValueError, match="figure = 'fig9'"):
        figures.draw("fig9", {}, [tmp_path / "x.png"], fig_settings())


def test_stribeck_law_limits():
    v = np.array([0.0, 1e-6, 10.0])
    mu = figures.stribeck_mu(v, 0.5, 0.3, 1000.0)
    assert mu[0] == pytest.approx(0.5) and mu[1] == pytest.approx(0.5, rel=1e-5)
    assert mu[2] == pytest.approx(0.3)
    assert figures.stribeck_mu(2.0, 0.5, 0.3, 0.0, 0.1) == pytest.approx(0.7)   # beta = 0: mu_s + gamma v


# ---------------------------------------------------------------------------------------------
# the record figures: Fig. 4 from a real record, and record versus pulse
# ---------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def record_sets():
    from isoslide.studies import record_study

    settings = record_study.records_settings(isoslide.config.load(None, {
        "records": {"names": ["Northridge_1994_PAC-175"], "pi2": {"start": 0.2, "stop": 0.8, "num": 2},
                    "pi3": [0.5, 1.0]}}))
    part = record_study.record_dataset("Northridge_1994_PAC-175", settings)
    return {"record": record_study.fig4_dataset(settings),
            "records": record_study.records_dataset([part], settings)}


def test_fig4_draws_the_stand_in_record(tmp_path, record_sets):
    out = tmp_path / "fig4.png"
    caption = figures.draw("fig4", {"record": record_sets["record"]}, [out], fig_settings(dpi=60))
    at = record_sets["record"].attrs
    assert caption.startswith("Fig. 4.") and "Kobe_1995_TAK-090" in caption
    assert "stands in" in caption and "RRS228" in caption
    assert f"T_p = {at['ricker_T_p']:.2f} s" in caption and f"R^2 = {at['ricker_r2']:.2f}" in caption
    assert "Mavroeidis-Papageorgiou" in caption
    assert figures.read_caption(out) == caption
    # without the record dataset: the Ricker wavelet alone, saying so
    assert "drawn alone" in figures.draw("fig4", {}, [tmp_path / "alone.png"], fig_settings(dpi=60))


def test_records_figure_states_the_numbers(tmp_path, record_sets):
    from isoslide.studies.record_study import ratio_summary

    ds = record_sets["records"]
    outs = [tmp_path / "records.png", tmp_path / "records.pdf"]
    caption = figures.draw("records", {"records": ds}, outs, fig_settings(dpi=60))
    a = ratio_summary(ds, ds.attrs["tolerance"]).sel(record="all")
    assert caption.startswith("Records.") and "Northridge_1994_PAC-175" in caption
    assert f"median {float(a['median_ratio']):.2f}" in caption
    assert f"only the pulse in {int(a['n_only_pulse'])}" in caption
    for p in outs:
        assert p.stat().st_size > 1000
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a2, b2 = tmp_path / "a" / "records.pdf", tmp_path / "b" / "records.pdf"
    figures.draw("records", {"records": ds}, [a2], fig_settings(dpi=50))
    figures.draw("records", {"records": ds}, [b2], fig_settings(dpi=50))
    assert a2.read_bytes() == b2.read_bytes()
