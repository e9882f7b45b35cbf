"""Mode resolution at events (isoslide.engine.modes): the order in which joint modes are tried."""

import numpy as np

from isoslide.engine.modes import candidates


def test_two_free_interfaces_try_sticking_first_then_one_slide_then_two():
    rows = candidates(np.array([True, True]), np.array([0.0, 0.0])).tolist()
    assert rows == [[0, 0], [0, 1], [0, -1], [1, 0], [-1, 0], [1, 1], [1, -1], [-1, 1], [-1, -1]]


def test_an_interface_that_is_not_free_keeps_its_mode():
    rows = candidates(np.array([True, False]), np.array([0.0, -1.0])).tolist()
    assert rows == [[0, -1], [1, -1], [-1, -1]]
    assert candidates(np.array([False, False]), np.array([1.0, 0.0])).tolist() == [[1, 0]]


def test_three_interfaces_are_ordered_by_the_number_sliding():
    rows = candidates(np.ones(3, dtype=bool), np.zeros(3))
    slides = (rows != 0.0).sum(axis=1)
    assert rows.shape == (27, 3) and np.all(np.diff(slides) >= 0)
    assert len({tuple(r) for r in rows.tolist()}) == 27


def test_a_rocking_block_that_is_not_free_keeps_its_mode_code():
    """A block rocking on its left corner (mode -4) or slide-rocking (+5) stays so while the bearing's modes are tried."""
    rows = candidates(np.array([False, True]), np.array([-4.0, 1.0])).tolist()
    assert rows == [[-4, 0], [-4, 1], [-4, -1]]
    assert candidates(np.array([False, True]), np.array([5.0, 0.0])).tolist() == [[5, 0], [5, 1], [5, -1]]
