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
    :mod:`isoslide.piecewise` ran instead of the integrator (a sampled record
    with Coulomb contents on a linear or fixed base, ``model="auto"``), e.g.
    ``coulomb+piecewise``, ``fixed-base+no-slide+piecewise``.
``regularized``, ``reference``
    A peer solver ran instead (``solve(..., method=...)``).

The general building (:mod:`isoslide.building`) adds, in front of the friction part:

``bilinear``, ``sliding-bearing``, ``linear``
    The isolator integrated (``fixed-base`` for ``Pi3 = 0``).
``flexible``
    The superstructure is flexible (``Pi12 > 0``) and integrated; ``roof``: the contents
    sit on it.
``bearing-stuck``, ``bearing-elastic``
    A reduction proved the sliding bearing never slips (the scene ran as the paper's fixed
    base) or the bilinear bearing never yields (the paper's linear isolator of its initial
    stiffness); followed by the paper model's label, e.g. ``bearing-stuck+fixed-base+coulomb``.

A general building runs Coulomb or Stribeck friction (``static-kinetic`` is the paper model's
limit only); a fixed base (``Pi3 = 0``) is a general building only with the contents on a
flexible superstructure's roof.

The position of a label in :data:`MODEL_LABELS` is its code in the ``model``
flag variable of every dataset; codes never change, new labels are appended.
"""

from __future__ import annotations

FRICTION_MODELS = ("coulomb", "stribeck", "static-kinetic")
"""Friction laws the exact solver integrates."""

PEER_LABELS = ("regularized", "reference")
"""Labels of the peer solvers ``solve(..., method=...)`` can run."""


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

ISOLATOR_PARTS = ("linear", "bilinear", "sliding-bearing", "fixed-base")
"""Isolator parts of a general building's label (the last for ``Pi3 = 0``)."""

BEARING_REDUCTIONS = ("bearing-stuck", "bearing-elastic")
"""Reductions of a bearing to the paper's model (see :mod:`isoslide.building`)."""


def building_label(isolator: str, flexible: bool, roof: bool, noslide: bool, friction: str,
                   oneway: bool) -> str:
    """The model label of a general building integrated by :mod:`isoslide.building_kernel`.

    Parameters
    ----------
    isolator : {"linear", "bilinear", "sliding-bearing", "fixed-base"}
        The isolator integrated.
    flexible : bool
        A flexible superstructure was integrated.
    roof : bool
        The contents sit on the superstructure (ignored unless ``flexible``).
    noslide, friction, oneway
        As for :func:`label`.
    """
    if isolator not in ISOLATOR_PARTS:
        raise ValueError(f"isolator = {isolator!r} is invalid; allowed: {ISOLATOR_PARTS}")
    if friction not in FRICTION_MODELS:
        raise ValueError(f"friction = {friction!r} is invalid; allowed: {FRICTION_MODELS}")
    parts = [isolator]
    if flexible:
        parts.append("flexible")
        if roof:
            parts.append("roof")
    if noslide:
        parts.append("no-slide")
    else:
        parts.append(friction)
        if oneway:
            parts.append("one-way")
    return "+".join(parts)


def _building_labels() -> tuple:
    out = []
    supers = ((False, False), (True, False), (True, True))
    for iso in ISOLATOR_PARTS:
        for flexible, roof in supers:
            if (iso == "linear" and not flexible) or (iso == "fixed-base" and not roof):
                continue   # the paper's model
            for noslide in (True, False):
                for friction in FRICTION_MODELS[:2]:
                    for oneway in (False, True):
                        name = building_label(iso, flexible, roof, noslide, friction, oneway)
                        if name not in out:
                            out.append(name)
    paper = [n for n in _exact_labels() + PIECEWISE_LABELS if "static-kinetic" not in n]
    for red in BEARING_REDUCTIONS:
        fixed = red == "bearing-stuck"
        out += [f"{red}+{n}" for n in paper if n.startswith("fixed-base") == fixed]
    return tuple(out)


BUILDING_LABELS = _building_labels()
"""Labels of the general building (appended after every other; codes never change)."""

MODEL_LABELS = (_STABLE + tuple(n for n in _exact_labels() + PEER_LABELS if n not in _STABLE)
                + PIECEWISE_LABELS)
MODEL_LABELS = MODEL_LABELS + tuple(n for n in BUILDING_LABELS if n not in MODEL_LABELS)
"""Every label :func:`isoslide.solve` can produce, in flag-code order (codes never change)."""
