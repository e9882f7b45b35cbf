"""isoslide.budget: phases logged by jobs, added up with the benchmark totals."""

import time

import pytest

from isoslide import budget
from isoslide.store.provenance import log_to


def _bench(path, seconds):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("s\th:m:s\tmax_rss\n" + f"{seconds}\t0:00:01\t100\n")


def test_phases_logged_by_a_job_are_read_back(tmp_path):
    log_file = tmp_path / "logs" / "solve_chunk" / "a" / "0.log"
    with log_to(log_file) as log:
        with budget.phase("solving", log):
            time.sleep(0.05)
        with budget.phase("writing", log):
            pass
    got = budget.job_phases(log_file)
    assert set(got) == {"start-up", "solving", "writing"}
    assert 0.05 <= got["solving"] < 5.0 and got["writing"] < 1.0
    assert 0.0 < got["start-up"] < 24 * 3600


def test_a_job_that_writes_its_result_logs_compilation_solving_the_result_and_writing(tmp_path):
    log_file = tmp_path / "logs" / "fig4_record" / "0.log"
    done = []
    with log_to(log_file) as log:
        got = budget.compile_solve_write(log, lambda: done.append("warm_up"), lambda: done.append("solve") or "result",
                                         lambda r: done.append(f"write {r}"))
    assert got == "result" and done == ["warm_up", "solve", "write result"]
    assert set(budget.job_phases(log_file)) == {"start-up", "compilation", "solving", "writing"}
    assert "INFO isoslide.job: result" in log_file.read_text()


def test_unknown_phase_is_refused():
    with pytest.raises(ValueError, match="phase = 'thinking'.*allowed"):
        with budget.phase("thinking"):
            pass


def test_budget_adds_phases_and_leaves_the_rest_as_other(tmp_path, capsys):
    for rel, total, phases in (("solve_chunk/s/0", 4.0, {"start-up": 2.0, "solving": 1.5}),
                               ("merge_study/s", 3.0, {"start-up": 2.5, "writing": 0.25})):
        _bench(tmp_path / "results" / "benchmarks" / f"{rel}.tsv", total)
        log_file = tmp_path / "logs" / f"{rel}.log"
        log_file.parent.mkdir(parents=True, exist_ok=True)
        log_file.write_text("".join(f"2026-01-01 00:00:00,000 INFO isoslide.job: phase {k} {v} s\n"
                                    for k, v in phases.items()))
    _bench(tmp_path / "results" / "benchmarks" / "report" / "accuracy.tsv", 6.0)
    snake_log = tmp_path / ".snakemake" / "log" / "2026-01-01T000000.000000.snakemake.log"
    snake_log.parent.mkdir(parents=True)
    snake_log.write_text("Building DAG\n[Thu Jan  1 00:00:00 2026]\nrule a:\n[Thu Jan  1 00:00:42 2026]\n")
    b = budget.budget(tmp_path)
    ph = b["phases"]
    assert b["jobs"] == 3 and b["job_seconds"] == pytest.approx(13.0)
    assert ph["start-up"] == {"jobs": 2, "seconds": pytest.approx(4.5)}
    assert ph["solving"]["seconds"] == pytest.approx(1.5) and ph["writing"]["seconds"] == pytest.approx(0.25)
    assert ph["reporting"] == {"jobs": 1, "seconds": pytest.approx(6.0)}
    assert ph["other"]["seconds"] == pytest.approx(13.0 - 4.5 - 1.5 - 0.25 - 6.0)
    assert sum(r["seconds"] for r in ph.values()) == pytest.approx(b["job_seconds"])
    assert b["wall_clock"] == 42.0
    assert budget.main([str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "reporting" in out and "wall-clock of the last run: 42 s" in out


def test_budget_without_a_run_says_so(tmp_path, capsys):
    assert budget.main([str(tmp_path)]) == 2
    assert "run the workflow first" in capsys.readouterr().err
