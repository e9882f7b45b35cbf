"""What the building peers share (isoslide.peers.stick_slip): the state's layout and the stick/slip bookkeeping."""

from dataclasses import dataclass

import numpy as np
import pytest

from isoslide.peers.stick_slip import X, XD, XS, StateIndex, bearing_event, candidates, choose_modes, farther


@dataclass(frozen=True)
class _Model(StateIndex):
    ms: np.ndarray
    kind: str


def test_a_rigid_superstructure_keeps_one_floor_slot_and_n_floors_take_two_each():
    rigid, three = _Model(np.zeros(0), "linear"), _Model(np.ones(3), "sliding")
    assert (X, XD, XS) == (0, 1, 2)
    assert (rigid.n, rigid.XSD, rigid.U, rigid.UD, rigid.FH) == (0, 3, 4, 5, 6)
    assert (three.n, three.XSD, three.U, three.UD, three.FH) == (3, 5, 8, 9, 10)
    assert three.holds and _Model(np.zeros(0), "fixed").holds and not rigid.holds


def test_an_interface_at_rest_tries_every_mode_and_a_moving_or_broken_one_keeps_its_direction():
    assert candidates(0, 0, 0.3) == ((0, 1, -1), True)
    assert candidates(0, 1, 0.0) == ((0, 1, -1), True)
    assert candidates(0, 1, -0.2) == ((-1,), False)
    assert candidates(-1, 0, 0.0) == ((-1,), False)


def _motion(xdd, udd, a_f, f_need):
    """Accelerations in the peers' layout ``(x_b'', ., u'', ., a_F, f_need)`` for every mode."""
    return lambda b, i: (xdd, None, udd, None, a_f, f_need)


def test_contents_within_their_limit_stick_and_past_it_slide_the_way_they_accelerate():
    B = _Model(np.zeros(0), "linear")
    y = np.zeros(7)
    assert choose_modes(B, y, 0, 0, 0, 0, 1.0, 0.0, _motion(0.0, 0.0, 0.5, 0.0)) == (0, 0)
    assert choose_modes(B, y, 0, 0, 0, 0, 1.0, 0.0, _motion(0.0, 2.0, 1.5, 0.0)) == (1, 0)


def test_a_sliding_bearing_within_its_strength_is_held_and_no_consistent_mode_gives_none():
    B = _Model(np.zeros(0), "sliding")
    y = np.zeros(7)
    assert choose_modes(B, y, 0, 0, 0, 0, 1.0, 1.0, _motion(0.0, 0.0, 0.5, 0.5)) == (0, 0)
    assert choose_modes(B, y, 0, 0, 0, 0, 1.0, 1.0, _motion(-3.0, 0.0, 0.5, 2.0)) == (0, -1)
    assert choose_modes(B, y, 0, 0, 0, 0, 1.0, 1.0, _motion(0.0, 0.0, 2.0, 2.0)) is None


def test_a_bilinear_bearing_yields_at_its_strength_and_unloads_from_it():
    y = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.9999])
    assert bearing_event("yield", y, 6, 1.0) == -1 and y[6] == -1.0
    y[6] = 0.99
    assert bearing_event("unload", y, 6, 1.0) == 0 and y[6] == 1.0


@pytest.mark.parametrize("u, expected", [(-0.3, (0.3, 2.0)), (0.1, (0.2, 1.0))])
def test_the_peak_slide_moves_only_to_a_farther_one(u, expected):
    assert farther(0.2, 1.0, u, 2.0) == expected
