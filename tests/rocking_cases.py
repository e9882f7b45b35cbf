"""Floor motions shared by the tests of the rocking peers (isoslide.peers.rocking and .slide_rock)."""

import math


def ricker(a_p, T_p):
    """Symmetric Ricker floor acceleration (m/s^2), peak a_p at t = 0, support [-2 T_p, 2 T_p)."""
    def f(t):
        if not -2 * T_p <= t < 2 * T_p:
            return 0.0
        s = (math.pi * t / T_p) ** 2
        return a_p * (1 - 2 * s) * math.exp(-s)
    return f


def rectangular(a, t_d):
    """Rectangular pulse (m/s^2): a on [0, t_d), else 0."""
    def f(t):
        return a if 0.0 <= t < t_d else 0.0
    return f
