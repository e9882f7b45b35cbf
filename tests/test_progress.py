"""Progress lines of long batch work: rate-limited, with scenes done, rate and time left."""

import functools
import logging

import pytest

import isoslide
from isoslide import solver
from isoslide.studies import sweep
from isoslide.store.progress import Progress


class _Clock:
    """A settable time source, s."""

    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_lines_are_rate_limited_and_state_done_rate_and_time_left(caplog):
    clock = _Clock()
    log = logging.getLogger("isoslide.test_progress")
    caplog.set_level(logging.INFO, logger=log.name)
    p = Progress(log, "batch", 1000, interval=5.0, clock=clock)
    for done, t in [(10, 1.0), (50, 4.9), (200, 5.0), (300, 9.0), (500, 10.0)]:
        clock.now = 100.0 + t
        p.update(done)
    clock.now = 100.0 + 20.0
    p.finish()
    assert caplog.messages == [
        "batch: 200 of 1000 scenes (20.0 %), 40 scenes/s, about 20 s left",
        "batch: 500 of 1000 scenes (50.0 %), 50 scenes/s, about 10 s left",
        "batch: 1000 of 1000 scenes (100.0 %), 50 scenes/s, done in 20 s",
    ]


def test_a_short_batch_or_a_disabled_log_writes_nothing(caplog):
    clock = _Clock()
    log = logging.getLogger("isoslide.test_progress")
    caplog.set_level(logging.INFO, logger=log.name)
    short = Progress(log, "short", 10, clock=clock)
    clock.now += 1.0
    short.update(5)
    short.finish()
    caplog.set_level(logging.WARNING, logger=log.name)
    quiet = Progress(log, "quiet", 10, clock=clock)
    clock.now += 1e6
    quiet.update(5)
    quiet.finish()
    assert caplog.messages == []
    with pytest.raises(ValueError, match="interval = 0 is out of range"):
        Progress(log, "x", 1, interval=0)


def test_solve_many_reports_progress_to_the_solver_log(caplog, monkeypatch):
    monkeypatch.setattr(solver, "Progress", functools.partial(Progress, interval=1e-9))
    caplog.set_level(logging.INFO, logger="isoslide.solver")
    scenes = [isoslide.Scene(pi2=p, pi3=1.0, pi4=0.1) for p in (0.1, 0.2, 0.3, 5.0)]
    batch = solver.solve_many(scenes)
    lines = [r.getMessage() for r in caplog.records if r.name == "isoslide.solver"]
    half = [m for m in lines if m.startswith("solve_many: 2 of 4 scenes (50.0 %), ")]
    assert len(half) == 1 and half[0].endswith(" s left") and "scenes/s, about " in half[0]
    assert lines[-1].startswith("solve_many: 4 of 4 scenes (100.0 %), ") and "done in" in lines[-1]
    assert list(batch.pi1) == [isoslide.solve(s).pi1 for s in scenes]


def test_study_chunk_logs_its_size_time_and_rate(caplog):
    config = isoslide.config.load(None, "config/test.yaml")
    spec = sweep.check_config(config)["fig3_newmark"]
    caplog.set_level(logging.INFO, logger="isoslide.studies.sweep")
    sweep.solve_chunk(spec, 0)
    done = [m for m in caplog.messages if "solved in" in m]
    assert len(done) == 1 and done[0].startswith(f"study {spec['study']}, chunk 0: ")
    assert "scenes/s)" in done[0]
