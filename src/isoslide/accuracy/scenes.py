"""The representative scene set: study subsamples and the hard cases; the buildings timed beside the paper's scene."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import records
from ..groups import INPUT_NAMES, group
from ..scene import Scene
from ..solver import peak_stuck_demand
from ..studies.sweep import build_grid, check_config
from .settings import PAPER_CONFIG, settings_from


@dataclass(frozen=True)
class Entry:
    """A scene of a scene set with its class and a readable label."""

    scene: Scene
    cls: str
    label: str
    study: str = ""


@dataclass(frozen=True)
class SceneSet:
    """An ordered list of :class:`Entry` (deterministic for a given configuration)."""

    entries: tuple = field(default_factory=tuple)

    def __len__(self):
        return len(self.entries)

    def __iter__(self):
        return iter(self.entries)

    def __getitem__(self, i):
        return self.entries[i]

    @property
    def scenes(self) -> list:
        """The scenes, in order."""
        return [e.scene for e in self.entries]

    def subset(self, n: int, avoid=("undamped", "long-period", "low-friction")) -> list[int]:
        """``n`` indices spread evenly over the set, spread over the classes.

        Classes in ``avoid`` (long runs) are used only when nothing else is left.
        """
        n = min(n, len(self))
        if n <= 0:
            return []
        by_class: dict = {}
        for i, e in enumerate(self.entries):
            by_class.setdefault(e.cls, []).append(i)
        order = [c for c in by_class if c not in avoid] + [c for c in by_class if c in avoid]
        picked: list[int] = []
        rank = 0
        while len(picked) < n:
            added = False
            for c in order:
                idx = by_class[c]
                if rank < len(idx):
                    # spread within the class: 0, last, middle, ...
                    j = _spread_order(len(idx))[rank]
                    picked.append(idx[j])
                    added = True
                    if len(picked) == n:
                        break
            if not added:
                break
            rank += 1
        return sorted(picked)


def _spread_order(n: int) -> list[int]:
    order, seen = [], set()
    for k in range(1, 64):
        for j in np.linspace(0, n - 1, min(n, 2 ** k - 1) if n > 1 else 1).round().astype(int):
            if int(j) not in seen:
                seen.add(int(j))
                order.append(int(j))
        if len(order) == n:
            break
    return order


def _label(sc: Scene) -> str:
    """Every input group and the pulse of ``sc``, as text."""
    parts = [f"{k}={getattr(sc, k):.4g}" for k in INPUT_NAMES]
    return " ".join(parts) + f" {sc.pulse.name}"


def study_entries(config: dict | None = None, per_study: int = 4, seed: int = 20240611) -> list[Entry]:
    """``per_study`` scenes drawn (fixed seed, without replacement) from every study's grid.

    Parameters
    ----------
    config : dict or None
        A pipeline configuration (``studies`` and the keys they inherit); ``None`` uses the
        paper's studies (:data:`PAPER_CONFIG`).
    """
    cfg = PAPER_CONFIG if not config or not config.get("studies") else config
    specs = check_config(cfg)
    out = []
    for name in sorted(specs):
        grid = build_grid(specs[name])
        rng = np.random.default_rng([seed, _stable_hash(name)])
        k = min(per_study, grid.size)
        idx = np.sort(rng.choice(grid.size, size=k, replace=False))
        for i, sc in zip(idx, grid.scenes(idx), strict=True):
            out.append(Entry(sc, "study", f"{name}[{int(i)}]", name))
    return out


def _stable_hash(text: str) -> int:
    h = 0
    for ch in text.encode():
        h = (h * 131 + ch) % (2**31 - 1)
    return h


def hard_scenes() -> list[Entry]:
    """The hard cases, by class (deterministic; thresholds computed by the solver)."""
    E = []

    def add(cls, **kw):
        sc = Scene(**kw)
        E.append(Entry(sc, cls, f"{cls}: {_label(sc)}"))

    # just below / just above the no-slide threshold: Pi2/Pi5 against the stuck demand A
    for pi3, pi4 in ((1.0, 0.1), (2.0, 0.05)):
        A = peak_stuck_demand(Scene(pi2=1.0, pi3=pi3, pi4=pi4), rtol=1e-12)
        for f in (1e-2, 1e-4, 1e-6):
            add("near-threshold", pi2=A * (1.0 - f), pi3=pi3, pi4=pi4)
        add("above-threshold", pi2=A * (1.0 + 1e-6), pi3=pi3, pi4=pi4)
    add("near-threshold", pi2=1.0 - 1e-4, pi3=0.0, pi4=0.0)              # fixed base, Ricker peak 1
    add("above-threshold", pi2=1.0 + 1e-9, pi3=0.0, pi4=0.0)
    A = peak_stuck_demand(Scene(pi2=1.0, pi3=1.0, pi4=0.1), rtol=1e-12)
    add("near-threshold", pi2=0.5 * A * (1.0 - 1e-3), pi3=1.0, pi4=0.1, pi5=0.5, pi6=1000.0)
    # resonance with light damping
    for pi4, pi2 in ((0.02, 0.02), (0.02, 0.1), (0.05, 0.05)):
        add("resonance", pi2=pi2, pi3=1.0, pi4=pi4)
    # xi_b -> 0 and over-damped
    add("undamped", pi2=0.05, pi3=1.0, pi4=0.0)
    add("undamped", pi2=0.1, pi3=2.0, pi4=0.0)
    add("undamped", pi2=0.05, pi3=1.0, pi4=1e-3)
    add("overdamped", pi2=0.05, pi3=1.0, pi4=1.0)
    add("overdamped", pi2=0.02, pi3=2.0, pi4=5.0)
    # very sharp Stribeck transitions
    for pi6 in (1e4, 1e5, 1e6):
        add("sharp-stribeck", pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.5, pi6=pi6)
    add("sharp-stribeck", pi2=0.03, pi3=1.0, pi4=0.1, pi5=0.05, pi6=1e4)
    add("sharp-stribeck", pi2=0.2, pi3=0.0, pi4=0.0, pi5=0.5, pi6=1e5)
    # heavy contents
    for pi8 in (0.3, 1.0, 10.0):
        add("heavy", pi2=0.1, pi3=1.0, pi4=0.1, pi8=pi8)
    add("heavy", pi2=0.1, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1000.0, pi8=1.0)
    # long isolation periods
    for pi3, pi2 in ((5.0, 0.02), (20.0, 0.01), (100.0, 0.005)):
        add("long-period", pi2=pi2, pi3=pi3, pi4=0.1)
    # strong viscous contact
    for pi7 in (10.0, 100.0):
        add("viscous", pi2=0.05, pi3=1.0, pi4=0.1, pi7=pi7)
    # nearly frictionless contents
    add("low-friction", pi2=1e-3, pi3=1.0, pi4=0.1)
    add("low-friction", pi2=1e-4, pi3=0.0, pi4=0.0)
    # very stiff bases
    add("stiff-base", pi2=0.2, pi3=1e-3, pi4=0.1)
    add("stiff-base", pi2=0.2, pi3=1e-2, pi4=0.0)
    # other pulses
    add("pulses", pi2=0.3, pi3=0.0, pi4=0.0, pulse="rectangular")
    add("pulses", pi2=0.1, pi3=1.0, pi4=0.1, pulse="antisymmetric_ricker")
    add("pulses", pi2=0.1, pi3=1.5, pi4=0.1, pulse="makris_cn")
    add("pulses", pi2=0.1, pi3=1.0, pi4=0.1, pi5=0.7, pi6=300.0, pulse="mavroeidis_papageorgiou")
    # the general building: bearings, flexible superstructures, contents on the roof
    add("friction-pendulum", pi2=0.1, pi3=3.0, pi4=0.0, pi8=0.01, pi9=0.05)
    add("friction-pendulum", pi2=0.05, pi3=2.5, pi4=0.0, pi8=0.1, pi9=0.1, pi5=0.7, pi6=1000.0)
    add("lead-rubber", pi2=0.1, pi3=2.5, pi4=0.05, pi8=0.01, pi9=0.05, pi10=0.005)
    add("flexible", pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi11=0.6, pi12=0.2, pi13=0.02)
    add("flexible", pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi11=0.6, pi12=0.2, pi13=0.02, floor="roof")
    add("flexible", pi2=0.08, pi3=3.0, pi4=0.0, pi8=0.01, pi9=0.05, pi11=0.6, pi12=0.3, pi13=0.02, floor="roof")
    add("strong-bearing", pi2=0.2, pi3=2.0, pi4=0.0, pi8=0.01, pi9=3.0)
    add("strong-bearing", pi2=0.2, pi3=1.0, pi4=2.0, pi8=0.1, pi9=1.0, pi10=0.01)
    return E


def scene_set(config: dict | None = None, settings: dict | None = None) -> SceneSet:
    """The representative scene set: study subsamples plus (if ``settings["hard"]``) the hard ones."""
    s = settings_from(settings if settings is not None else config)
    entries = study_entries(config, s["per_study"], s["seed"])
    if s["hard"]:
        entries += hard_scenes()
    return SceneSet(tuple(entries))


def scene_coords(entries) -> dict:
    """Coordinates along ``scene`` of a dataset over ``entries``: number, input groups, pulse, class, label."""
    coords = {"scene": ("scene", np.arange(len(entries), dtype=np.int32),
                        {"long_name": "scene number in the accuracy scene set", "units": "1"})}
    for k in INPUT_NAMES:
        coords[k] = ("scene", np.array([getattr(e.scene, k) for e in entries], dtype=float), group(k).attrs())
    coords["pulse"] = ("scene", np.array([e.scene.pulse.name for e in entries], dtype=str),
                       {"long_name": "ground-acceleration pulse shape", "units": "1"})
    coords["scene_class"] = ("scene", np.array([e.cls for e in entries], dtype=str),
                             {"long_name": "scene class: study subsample or hard case", "units": "1"})
    coords["scene_label"] = ("scene", np.array([e.label for e in entries], dtype=str),
                             {"long_name": "scene description", "units": "1"})
    return coords


BUILDING_POINTS = [dict(pi2=pi2, pi3=pi3, pi4=0.05, pi8=0.01) for pi2 in (0.05, 0.1, 0.2, 0.3) for pi3 in (2.0, 3.0)]
"""Pi points of the buildings section: the paper's model at each, and every building beside it."""
STOREYS = (2, 5, 8)
"""Storey counts of the uniform N-storey buildings timed beside the others."""
STOREYS_NAME = "{} storeys, contents on the roof"
"""Row name of the uniform building of ``n`` storeys (``STOREYS_NAME.format(n)``)."""
BUILDINGS = {
    "paper model (linear isolator, rigid)": {},
    "friction pendulum (pi9 = 0.05)": dict(pi9=0.05),
    "speed-dependent pendulum (pi9 0.1, pi22 0.5)": dict(pi9=0.1, pi22=0.5, pi23=20.0),
    "triple friction pendulum (pi9 0.05, pi24 0.1)": dict(pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0,
                                                          pi28=0.05, pi29=0.1, pi30=0.2),
    "lead-rubber bearing (pi9 = 0.05, pi10 = 0.005)": dict(pi9=0.05, pi10=0.005),
    "flexible superstructure, contents on the base": dict(pi11=0.6, pi12=0.2, pi13=0.02),
    "flexible superstructure, contents on the roof": dict(pi11=0.6, pi12=0.2, pi13=0.02, floor="roof"),
    "friction pendulum, flexible, roof": dict(pi9=0.05, pi11=0.6, pi12=0.2, pi13=0.02, floor="roof"),
    **{STOREYS_NAME.format(n): dict(pi11=0.6, pi12=0.2, pi13=0.02, storeys=n, floor="roof")
       for n in STOREYS},
}
"""Buildings timed side by side on :data:`BUILDING_POINTS` (keyword arguments of :class:`isoslide.Scene`).

The speed-dependent friction pendulum breaks away at the constant one's strength (``Pi9 Pi22 = 0.05``)
and slides against up to twice it (``Pi23 = 20``).  The triple friction pendulum has the constant one's
period of regime III (``Pi3``, radius ``L2 + L3``) and its friction on the outer surface 1 (``mu2``,
``Pi9 = 0.05``), ``L1 = 0.1 (L2 + L3)``, ``L2 = L3`` and ``mu1 : mu2 : mu3 = 0.5 : 1 : 2``; on these points
its bearing reaches regime III (at ``Pi3 = 2`` it is the bearing of the scene ``"III"`` of
:data:`isoslide.peers.opensees_tfp.BUILDING_SCENES`)."""
SPEED_PENDULUM = "speed-dependent pendulum (pi9 0.1, pi22 0.5)"
"""Row of the friction pendulum whose friction rises with speed, timed against :data:`PENDULUM`."""
TFP_PENDULUM = "triple friction pendulum (pi9 0.05, pi24 0.1)"
"""Row of the triple friction pendulum, timed against :data:`PENDULUM` (and OpenSees's
``TripleFrictionPendulum`` element in :mod:`isoslide.accuracy.opensees_cost`)."""
TARGET_TFP_RATIO = 2.0
"""Aim: isoslide's cost on the triple friction pendulum at most this many times its cost on :data:`PENDULUM`."""
PENDULUM = "friction pendulum (pi9 = 0.05)"
"""Row of the constant-friction pendulum."""

PLANAR_POINTS = [dict(pi2=pi2, pi3=pi3, pi4=0.1) for pi2 in (0.1, 0.2, 0.3) for pi3 in (1.0, 2.0)]
"""Pi points of the planar scenes of the bench: every building of :data:`PLANAR_BUILDINGS` at each."""
PLANAR_EXCITATION = dict(pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.7)
"""The planar scenes' excitation: a Ricker pulse along x, an antisymmetric Ricker of 0.7 a_p along y."""
PLANAR_BUILDINGS = {
    "fixed base": dict(pi3=0.0),
    "linear isolator, two-way coupling (pi8 = 0.2)": dict(pi8=0.2),
    "Stribeck contents (pi5 = 0.7, pi6 = 20)": dict(pi5=0.7, pi6=20.0),
    "3 storeys, contents on the roof": dict(pi11=0.6, pi12=0.2, pi13=0.02, storeys=3, floor="roof"),
}
"""Buildings of the planar scenes of the bench (keyword arguments of :class:`isoslide.Scene` over each point)."""
PAIR_SUITE = "fema-p695-near-field-pulse"
"""Suite whose recorded pairs the bench times."""
PAIR_POINTS = {"isolated": dict(pi2=0.2, pi3=2.0, pi4=0.1), "fixed base": dict(pi2=0.2, pi3=0.0, pi4=0.1)}
"""Pi points at which each recorded pair runs as recorded."""
PAIR_LAG = 0.25
"""Lag (units of T_p) of a bundled record paired with itself when :data:`PAIR_SUITE` is unavailable."""


def recorded_pairs(n: int, suite_name: str = PAIR_SUITE) -> tuple:
    """``(source, [(name, x, y, lag), ...])``: the suite's first ``n`` pairs, or bundled records lagged.

    When the suite cannot be read, each of the first ``n`` bundled samples is paired with itself
    lagged by :data:`PAIR_LAG` of its fitted period (a planar excitation of one record).
    """
    try:
        motions = records.suite(suite_name)
    except (ValueError, ImportError, OSError) as exc:
        names = records.samples()[:n]
        return (f"bundled samples paired with themselves lagged by {PAIR_LAG:g} T_p ({suite_name} unavailable: "
                f"{' '.join(str(exc).split())})",
                [(nm, records.sample(nm), records.sample(nm), PAIR_LAG) for nm in names])
    return suite_name, [(gm.name, gm.x, gm.y, 0.0) for gm in motions[:n]]
