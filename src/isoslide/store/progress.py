"""Progress of long batch work, logged at most every few seconds.

:class:`Progress` is told how many items are done (:meth:`Progress.update`)
and logs, at most once per ``interval`` seconds, how many are done, the rate
and the estimated time left::

    solve_many: 1200 of 2000 scenes (60.0 %), 850 scenes/s, about 0.9 s left

An update costs one clock read and one comparison, so it can sit in a loop of
sub-millisecond solves.  A batch that ends before the first report logs
nothing; one that reported logs a last line when it ends (:meth:`Progress.finish`).
"""

from __future__ import annotations

import logging
import time

__all__ = ["DEFAULT_INTERVAL", "Progress"]

DEFAULT_INTERVAL = 5.0
"""Shortest time between two progress lines, s."""


class Progress:
    """Rate-limited progress lines for a batch of ``total`` items.

    Parameters
    ----------
    log : logging.Logger
        Where the lines go (level INFO).
    what : str
        Label that starts every line, e.g. ``"solve_many"``.
    total : int
        Number of items in the batch.
    unit : str
        Name of the items, plural (default ``"scenes"``).
    interval : float
        Shortest time between two lines, s (> 0).
    clock : callable
        Time source in seconds (default :func:`time.monotonic`).
    """

    __slots__ = ("_clock", "_log", "_next", "_reported", "_start", "interval", "total", "unit", "what")

    def __init__(self, log: logging.Logger, what: str, total: int, unit: str = "scenes",
                 interval: float = DEFAULT_INTERVAL, clock=time.monotonic):
        if not interval > 0:
            raise ValueError(f"interval = {interval!r} is out of range; allowed range: 0 < interval < inf (s)")
        self._log, self.what, self.total, self.unit, self.interval = log, what, int(total), unit, float(interval)
        self._clock = clock
        self._start = clock()
        # a disabled logger never reports: the next report is never due
        self._next = self._start + self.interval if log.isEnabledFor(logging.INFO) else float("inf")
        self._reported = False

    def update(self, done: int) -> None:
        """Note that ``done`` items are finished; log a line if the last one is ``interval`` s old."""
        now = self._clock()
        if now >= self._next:
            self._report(done, now)
            self._next = now + self.interval

    def finish(self, done: int | None = None) -> None:
        """Log the final line (only if a progress line was logged before)."""
        if self._reported:
            self._report(self.total if done is None else done, self._clock())

    def _report(self, done: int, now: float) -> None:
        elapsed = max(now - self._start, 1e-12)
        rate = done / elapsed
        left = self.total - done
        pct = 100.0 * done / self.total if self.total else 100.0
        if left > 0:
            eta = f"about {left / rate:.3g} s left" if rate > 0 else "time left unknown"
        else:
            eta = f"done in {elapsed:.3g} s"
        self._log.info("%s: %d of %d %s (%.1f %%), %.4g %s/s, %s", self.what, done, self.total, self.unit,
                       pct, rate, self.unit, eta)
        self._reported = True
