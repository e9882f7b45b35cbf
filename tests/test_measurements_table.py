"""The bench rewrites its own rows of the measurements table, in place, and nothing else."""

import csv
import shutil
from pathlib import Path

import pytest

from isoslide.accuracy import measurements as ms

DOCS_TABLE = Path(__file__).resolve().parent.parent / "docs" / "measurements.csv"


def _rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_the_documentation_table_has_the_columns_the_bench_writes():
    assert tuple(_rows(DOCS_TABLE)[0]) == ms.FIELDS


def test_rewriting_a_command_rows_keeps_every_other_row_and_their_order(tmp_path):
    path = tmp_path / "m.csv"
    shutil.copy(DOCS_TABLE, path)
    before = _rows(path)
    mine = [i for i, r in enumerate(before) if r["topic"] == "buildings" and r["command"] == ms.BUILDINGS_COMMAND]
    assert mine, "the table has rows of the buildings section"
    new = [ms.Measurement("paper model: cost per scene", "123.4", "us", "test"),
           ms.Measurement("a class: cost ratio to the paper model", "2.00", "x")]
    replaced = ms.write_rows(path, "buildings", ms.BUILDINGS_COMMAND, new, date="2026-01-02", commit="abc1234")
    after = _rows(path)
    assert replaced == len(mine)
    assert len(after) == len(before) - len(mine) + len(new)
    others = [r for i, r in enumerate(before) if i not in set(mine)]
    assert [r for r in after if not (r["topic"] == "buildings" and r["command"] == ms.BUILDINGS_COMMAND)] == others
    at = mine[0]
    assert [r["quantity"] for r in after[at:at + 2]] == [m.quantity for m in new]
    assert after[at]["date"] == "2026-01-02" and after[at]["commit"] == "abc1234" and after[at]["value"] == "123.4"


def test_a_topic_new_to_the_table_is_appended(tmp_path):
    path = tmp_path / "m.csv"
    shutil.copy(DOCS_TABLE, path)
    n = len(_rows(path))
    assert ms.write_rows(path, "new_topic", "python -m x", [ms.Measurement("q", "1", "s")], date="2026-01-02",
                         commit="abc") == 0
    rows = _rows(path)
    assert len(rows) == n + 1 and rows[-1]["topic"] == "new_topic"


def test_a_table_with_other_columns_is_refused_and_left_untouched(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("topic,value\nx,1\n")
    with pytest.raises(ValueError, match="columns"):
        ms.write_rows(path, "x", "c", [ms.Measurement("q", "1", "s")])
    assert path.read_text() == "topic,value\nx,1\n"


def test_building_rows_carry_the_paper_cost_and_every_ratio():
    summary = {"paper": {"us": 140.0, "ratio": 1.0, "err_max": 1e-9},
               "pendulum": {"us": 300.0, "ratio": 2.1, "err_max": 3e-9, "pendulum_ratio": 0.8}}
    rows = ms.buildings_rows(summary, "paper", points=8, repeats=7)
    assert rows[0].value == "140.0" and rows[0].unit == "us" and "8 Pi points" in rows[0].conditions
    assert rows[1].value == "2.10" and "0.80" in rows[1].conditions
    assert rows[-1].value == "3.0e-09"


def test_building_rows_say_what_limits_each_class():
    summary = {"paper": {"us": 140.0, "ratio": 1.0, "err_max": 1e-9},
               "flexible": {"us": 700.0, "ratio": 5.0, "err_max": 2e-9, "steps_ratio": 4.0, "step_cost_ratio": 1.25,
                            "assembly_us": 175.0, "assembly_share": 0.25, "assembly_cold_us": 410.0}}
    (row,) = ms.buildings_rows(summary, "paper", points=8, repeats=7)[1:-1]
    assert row.conditions == ("steps x4.00, cost per step x1.25, assembly 175 us (25 % of its cost; 410 us with "
                              "nothing shared with another scene)")


def test_rocking_rows_carry_the_ratio_what_limits_it_and_the_records_cost():
    summary = {"ratio_median": 1.2, "ratio_max": 5.5, "rows": 24, "slow": 3, "slow_steps_ratio": 4.0,
               "slow_step_cost_ratio": 2.5, "records": 18, "rock_ns_per_sample": 900.0, "slide_ns_per_sample": 90.0}
    rows = ms.rocking_rows(summary, repeats=7)
    assert [r.value for r in rows] == ["1.20 / 5.50", "4.0 / 2.5", "900 / 90"]
    assert "24 scenes" in rows[0].conditions and "3 scenes" in rows[1].conditions and "18 records" in rows[2].conditions
    assert len(ms.rocking_rows({"ratio_median": 1.0, "ratio_max": 2.0, "rows": 4}, repeats=3)) == 1


def test_planar_rows_carry_each_buildings_ratio_the_pairs_cost_per_sample_and_the_studys_cpu_time():
    scenes = {"fixed base": {"ratio": 10.2, "err_max": 5e-9}, "3 storeys": {"ratio": 2.1, "err_max": 3e-10}}
    pairs = {"isolated": {"us_per_sample_median": 1.8, "us_per_sample_1d_median": 0.07},
             "fixed base": {"us_per_sample_median": 3.3, "us_per_sample_1d_median": 0.068},
             "us_per_sample_median": 2.1, "met": False}
    frag = {"config": "x.yaml", "analyses": 16000, "sampled": [1, 2, 3, 4],
            "isolated": {"mean_ms": 30.0}, "fixed_base": {"mean_ms": 60.0}}
    rows = ms.planar_rows({"scenes": scenes, "pairs": pairs, "fragility": frag}, 7, 3.0, 0.5)
    assert [r.value for r in rows] == ["10.2 / 2.1", "5.0e-09", "2.10", "8.0 / 16.0"]
    assert rows[0].quantity.endswith("fixed base / 3 storeys") and "largest fixed base" in rows[0].conditions
    assert "goal 0.5" in rows[2].quantity and "isolated 1.80" in rows[2].conditions
    assert "16000 analyses per building" in rows[3].quantity and rows[3].unit == "CPU-min"
    assert len(ms.planar_rows({"scenes": scenes, "pairs": pairs, "fragility": None}, 3, 3.0, 0.5)) == 3
