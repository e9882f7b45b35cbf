"""The labels of the mechanical models a solve can run, in one list.

:attr:`isoslide.Solution.model` names the smallest exact model that ran for a
scene, as parts joined by ``+``:

``fixed-base``
    ``Pi3 = 0``: the floor moves with the ground; the base is not integrated.
``no-slide``
    The floor demand never reaches ``mu_s g``: ``Pi1 = 0`` exactly.
``coulomb``
    Friction independent of sliding speed; the Stribeck terms are skipped.
``stribeck``
    The full Stribeck law of the paper's Eq. 1.
``static-kinetic``
    The limit ``Pi6 -> inf`` (``solve(..., model="static-kinetic")``): stick up to
    ``mu_s``, kinetic ``mu_k`` at any sliding speed.
``one-way``
    The block's back-reaction on the base is dropped (``Pi8 = 0``, or proven
    below the accuracy target).
``piecewise``
    Appended to the label when the exact piecewise propagation of
    :mod:`isoslide.engine.piecewise` ran instead of the integrator (a sampled record
    with Coulomb contents on a linear or fixed base, ``model="auto"``), e.g.
    ``coulomb+piecewise``, ``fixed-base+no-slide+piecewise``.
``regularized``, ``reference``
    A peer solver ran instead (``solve(..., method=...)``).
``planar``
    Appended when the contents slid in the plane under two horizontal ground components that are
    not along one line (:mod:`isoslide.engine.planar_kernel`), e.g. ``fixed-base+coulomb+planar``;
    an excitation along one line runs the 1-D model along it.

The general building (:mod:`isoslide.engine.building`) adds, in front of the friction part:

``bilinear``, ``sliding-bearing``, ``sliding-bearing-speed``, ``triple-friction-pendulum``, ``linear``
    The isolator integrated (``fixed-base`` for ``Pi3 = 0``); ``sliding-bearing-speed`` is a
    sliding bearing whose friction rises with its speed (``Pi22 < 1``, ``Pi23 > 0``),
    ``triple-friction-pendulum`` one with an articulated slider (``Pi24 > 0``), and
    ``triple-friction-pendulum-speed`` that one with its surfaces' friction rising with speed.
``flexible``
    The superstructure is flexible (``Pi12 > 0``) and integrated; ``roof``: the contents
    sit on its top floor, ``intermediate``: on a floor between the slab and the roof.
``bearing-stuck``, ``bearing-elastic``
    A reduction proved the sliding bearing never slips (the scene ran as the paper's fixed
    base) or the bilinear bearing never yields (the paper's linear isolator of its initial
    stiffness); followed by the paper model's label, e.g. ``bearing-stuck+fixed-base+coulomb``.

A general building runs Coulomb or Stribeck friction (``static-kinetic`` is the paper model's
limit only); a fixed base (``Pi3 = 0``) is a general building only with the contents on a
flexible superstructure's roof.

The label is derived from the model's :class:`Facets` (one value per independent property,
:data:`FACETS`) and whether the contents slid (``Pi1 > 0``); datasets store the facets, one small
flag variable each (``model_isolator``, ..., see :data:`isoslide.datasets.FACET_VARIABLES`), and
:func:`isoslide.datasets.model_labels` derives the labels back.  :data:`MODEL_LABELS` lists every
label a solve can produce (new labels are appended).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

FRICTION_MODELS = ("coulomb", "stribeck", "static-kinetic")
"""Friction laws the exact solver integrates."""

PEER_LABELS = ("regularized", "reference")
"""Labels of the peer solvers ``solve(..., method=...)`` can run."""

FACETS = {
    "isolator": ("linear", "fixed-base", "bilinear", "sliding-bearing", "sliding-bearing-speed",
                 "triple-friction-pendulum", "triple-friction-pendulum-speed"),
    "superstructure": ("rigid", "flexible"),
    "floor": ("base", "roof", "intermediate"),
    "friction": FRICTION_MODELS,
    "coupling": ("two-way", "one-way"),
    "reduction": ("none", "bearing-stuck", "bearing-elastic", "demand-bound"),
    "propagation": ("integrated", "piecewise", "none", "exponential"),
    "solver": ("exact",) + PEER_LABELS,
    "vertical": ("none", "normal-force"),
    "contact": ("line", "plane"),
    "contents": ("sliding", "rocking"),
}
"""The independent properties of the model that ran, and the values each can take.

``isolator``: the isolator integrated (``fixed-base`` for a base held to the ground: ``Pi3 = 0``,
or a sliding bearing proven never to slip); ``superstructure``: rigid, or flexible and
integrated; ``floor``: the contents' floor (the slab, the roof, or a floor between); ``friction``:
the contact law integrated (``coulomb`` when friction does not depend on speed);
``coupling``: the contents' friction acts back on the building (``two-way``) or is dropped
(``one-way``: ``Pi8 = 0``, proven below the accuracy target, or a base that does not move);
``reduction``: a proof that replaced the scene by a smaller model (a sliding bearing that never
slips, a bilinear bearing that never yields, or a floor demand below the stick limit:
``demand-bound``, answered ``Pi1 = 0`` without integrating); ``propagation``: integrated, the
exact piecewise propagation of a sampled record, none, or the exact propagation of a linearly
isolated flexible building between the contents' transitions (:mod:`isoslide.engine.exponential`);
``solver``: the exact solver or a peer;
``vertical``: vertical ground motion acting through the normal forces, or none; ``contact``: the
contents slide on a line (the 1-D model, along the excitation's direction) or in the plane;
``contents``: contents that only slide, or a block that can rock (it tips before it slides,
:attr:`isoslide.Scene.tips`), whose modes :attr:`isoslide.Solution.modes` lists.
The position of a value is its code in the dataset flag variable ``model_<facet>``; values are
only ever appended."""


def label(fixed: bool, noslide: bool, friction: str, oneway: bool, piecewise: bool = False) -> str:
    """The model label of an exact solve.

    Parameters
    ----------
    fixed : bool
        The base is fixed (``Pi3 = 0``).
    noslide : bool
        The block never slid.
    friction : {"coulomb", "stribeck", "static-kinetic"}
        The friction law integrated.
    oneway : bool
        The back-reaction on the base was dropped (ignored for a fixed base).
    piecewise : bool
        The exact piecewise propagation ran (Coulomb friction only).
    """
    if friction not in FRICTION_MODELS:
        raise ValueError(f"friction = {friction!r} is invalid; allowed: {FRICTION_MODELS}")
    parts = ["fixed-base"] if fixed else []
    if noslide:
        parts.append("no-slide")
    else:
        parts.append(friction)
        if oneway and not fixed:
            parts.append("one-way")
    if piecewise:
        if friction != "coulomb":
            raise ValueError(f"piecewise = True needs friction = 'coulomb', got friction = {friction!r}")
        parts.append("piecewise")
    return "+".join(parts)


def _exact_labels() -> tuple:
    out = []
    for fixed in (False, True):
        for noslide in (True, False):
            for friction in FRICTION_MODELS:
                for oneway in (False, True):
                    name = label(fixed, noslide, friction, oneway)
                    if name not in out:
                        out.append(name)
    return tuple(out)


_STABLE = ("no-slide", "fixed-base+no-slide", "coulomb", "coulomb+one-way", "stribeck",
           "stribeck+one-way", "fixed-base+coulomb", "fixed-base+stribeck", "regularized", "reference")

def _piecewise_labels() -> tuple:
    out = []
    for fixed in (False, True):
        for noslide in (True, False):
            for oneway in (False, True):
                name = label(fixed, noslide, "coulomb", oneway, piecewise=True)
                if name not in out:
                    out.append(name)
    return tuple(out)


PIECEWISE_LABELS = _piecewise_labels()
"""Labels of the exact piecewise propagation (appended after the integrator's and the peers')."""

ISOLATOR_PARTS = ("linear", "bilinear", "sliding-bearing", "fixed-base", "sliding-bearing-speed",
                  "triple-friction-pendulum", "triple-friction-pendulum-speed")
"""Isolator parts of a general building's label (the last for ``Pi3 = 0``)."""

BEARING_REDUCTIONS = ("bearing-stuck", "bearing-elastic")
"""Reductions of a bearing to the paper's model (see :mod:`isoslide.engine.building`)."""


def building_label(isolator: str, flexible: bool, floor, noslide: bool, friction: str,
                   oneway: bool) -> str:
    """The model label of a general building integrated by :mod:`isoslide.engine.building_kernel`.

    Parameters
    ----------
    isolator : {"linear", "bilinear", "sliding-bearing", "fixed-base", "sliding-bearing-speed", \
"triple-friction-pendulum", "triple-friction-pendulum-speed"}
        The isolator integrated.
    flexible : bool
        A flexible superstructure was integrated.
    floor : {"base", "roof", "intermediate"} or bool
        The contents' floor (:data:`FACETS` ``["floor"]``; ignored unless ``flexible``); ``True``
        stands for ``"roof"``, ``False`` for ``"base"``.
    noslide, friction, oneway
        As for :func:`label`.
    """
    if isolator not in ISOLATOR_PARTS:
        raise ValueError(f"isolator = {isolator!r} is invalid; allowed: {ISOLATOR_PARTS}")
    if friction not in FRICTION_MODELS:
        raise ValueError(f"friction = {friction!r} is invalid; allowed: {FRICTION_MODELS}")
    floor = {True: "roof", False: "base"}.get(floor, floor)
    if floor not in FACETS["floor"]:
        raise ValueError(f"floor = {floor!r} is invalid; allowed: {FACETS['floor']}")
    parts = [isolator]
    if flexible:
        parts.append("flexible")
        if floor != "base":
            parts.append(floor)
    if noslide:
        parts.append("no-slide")
    else:
        parts.append(friction)
        if oneway:
            parts.append("one-way")
    return "+".join(parts)


def _building_labels(floors=("base", "roof"), rigid: bool = True, isolators=ISOLATOR_PARTS[:6]) -> tuple:
    out = []
    supers = (((False, "base"),) if rigid else ()) + tuple((True, f) for f in floors)
    for iso in isolators:
        for flexible, floor in supers:
            if (iso == "linear" and not flexible) or (iso == "fixed-base" and floor == "base"):
                continue   # the paper's model
            for noslide in (True, False):
                for friction in FRICTION_MODELS[:2]:
                    for oneway in (False, True):
                        name = building_label(iso, flexible, floor, noslide, friction, oneway)
                        if name not in out:
                            out.append(name)
    if floors != ("base", "roof") or isolators != ISOLATOR_PARTS[:6]:
        return tuple(out)
    paper = [n for n in _exact_labels() + PIECEWISE_LABELS if "static-kinetic" not in n]
    for red in BEARING_REDUCTIONS:
        fixed = red == "bearing-stuck"
        out += [f"{red}+{n}" for n in paper if n.startswith("fixed-base") == fixed]
    return tuple(out)


BUILDING_LABELS = _building_labels()
BUILDING_LABELS = BUILDING_LABELS + _building_labels(("intermediate",), rigid=False)
"""Labels of the general building; contents on a floor between the slab and the roof of a building
of several storeys come last."""

MODEL_LABELS = (_STABLE + tuple(n for n in _exact_labels() + PEER_LABELS if n not in _STABLE)
                + PIECEWISE_LABELS)
MODEL_LABELS = MODEL_LABELS + tuple(n for n in BUILDING_LABELS if n not in MODEL_LABELS)
VERTICAL_LABELS = tuple(f"{n}+vertical" for n in _exact_labels() + _building_labels(("base", "roof", "intermediate"))
                        if "static-kinetic" not in n)
"""Labels of the general building under vertical ground motion (every reduction is off there)."""
MODEL_LABELS = MODEL_LABELS + VERTICAL_LABELS
PLANAR_ISOLATORS = ("linear", "fixed-base", "sliding-bearing", "sliding-bearing-speed")
"""Isolators of a building in the plane (a bilinear bearing's circular yield surface is not modelled)."""
PLANAR_LABELS = tuple(f"{n}+planar{v}" for v in ("", "+vertical")
                      for n in _exact_labels() + _building_labels(("base", "roof", "intermediate"))
                      if "static-kinetic" not in n and n.split("+")[0] in PLANAR_ISOLATORS + ("no-slide", "coulomb",
                                                                                            "stribeck"))
"""Labels of planar sliding (two horizontal ground components not along one line), with and without
vertical motion: a fixed base, a linear isolator or a sliding bearing, its friction constant or rising
with speed (:data:`PLANAR_ISOLATORS`)."""
MODEL_LABELS = MODEL_LABELS + PLANAR_LABELS
ROCKING_LABELS = tuple(f"{n}+rocking{v}" for v in ("", "+vertical")
                       for n in _exact_labels() + _building_labels(("base", "roof", "intermediate"))
                       if "static-kinetic" not in n and "stribeck" not in n and "piecewise" not in n)
"""Labels of contents that can rock (Coulomb friction, in line, with and without vertical motion)."""
MODEL_LABELS = MODEL_LABELS + ROCKING_LABELS
TFP_SPEED_LABELS = tuple(f"{n}{v}" for v in ("", "+vertical")
                         for n in _building_labels(("base", "roof", "intermediate"), isolators=ISOLATOR_PARTS[6:]))
"""Labels of a triple pendulum whose friction rises with speed (:mod:`isoslide.engine.tfp_flow`; in line,
contents that slide)."""
MODEL_LABELS = MODEL_LABELS + TFP_SPEED_LABELS
"""Every label :func:`isoslide.solve` can produce."""


@dataclass(frozen=True)
class Facets:
    """The model that ran for a scene, one value per independent property (:data:`FACETS`).

    :meth:`label` derives the display label (:attr:`isoslide.Solution.model`) from them; whether
    the contents slid is ``Pi1 > 0``, not part of the model.
    """

    isolator: str = "linear"
    superstructure: str = "rigid"
    floor: str = "base"
    friction: str = "coulomb"
    coupling: str = "two-way"
    reduction: str = "none"
    propagation: str = "integrated"
    solver: str = "exact"
    vertical: str = "none"
    contact: str = "line"
    contents: str = "sliding"

    def __post_init__(self):
        for name, allowed in FACETS.items():
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} = {getattr(self, name)!r} is invalid; allowed: {allowed}")

    def label(self, slid: bool = True) -> str:
        """The display label, e.g. ``"sliding-bearing+flexible+roof+coulomb"`` (see the module docstring).

        Parameters
        ----------
        slid : bool
            Whether the contents slid (``Pi1 > 0``); ``False`` puts ``no-slide`` in place of the
            friction law.
        """
        if self.solver != "exact":
            return self.solver
        if self.vertical != "none":
            return f"{replace(self, vertical='none').label(slid)}+vertical"
        if self.contact != "line":
            return f"{replace(self, contact='line').label(slid)}+planar"
        if self.contents != "sliding":
            return f"{replace(self, contents='sliding').label(slid)}+rocking"
        oneway = self.coupling == "one-way"
        fixed = self.isolator == "fixed-base"
        piecewise = self.propagation == "piecewise"
        if self.reduction in BEARING_REDUCTIONS:
            return f"{self.reduction}+{label(fixed, not slid, self.friction, oneway, piecewise)}"
        if self.isolator in ISOLATOR_PARTS[1:3] + ISOLATOR_PARTS[4:] or \
                self.superstructure == "flexible":
            return building_label(self.isolator, self.superstructure == "flexible", self.floor, not slid,
                                  self.friction, oneway)
        return label(fixed, not slid, self.friction, oneway, piecewise)

    def codes(self) -> dict:
        """``{facet: code}``: each value's position in :data:`FACETS`."""
        return {name: FACETS[name].index(getattr(self, name)) for name in FACETS}
