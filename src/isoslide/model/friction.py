"""The Stribeck friction law of the contents, written once.

The paper's Eq. 1: ``mu(v) = mu_s sech(beta v) + mu_k (1 - sech(beta v)) + gamma |v|``; the friction
force on a block sliding at speed ``|v|`` under the normal force ``N`` has the magnitude
``N mu(|v|)``.  In the model's units (forces per unit contents' mass ``m_EC a_p``, speeds
``a_p T_p``) the coefficients become the Pi-groups: ``mu_s g / a_p = Pi2/Pi5``,
``mu_k g / a_p = Pi2``, ``beta a_p T_p = Pi6``, ``gamma g T_p = Pi7`` and ``N = 1`` on a floor
without vertical motion.

:func:`stribeck` takes scalars or numpy arrays and compiles unchanged under numba, so the
compiled solvers, the history tables and the figures evaluate the same expression.
"""

from __future__ import annotations

import numpy as np


def stribeck(v, mu_s, mu_k, beta, gamma, normal=1.0):
    """Friction force magnitude ``N mu(|v|)`` and its slope ``d (N mu) / d|v|``.

    Parameters
    ----------
    v : float or ndarray
        Sliding velocity (its sign is ignored), in the units that make ``beta v`` and
        ``gamma v`` dimensionless (m/s with SI coefficients; ``a_p T_p`` with Pi-groups).
    mu_s, mu_k : float
        Static and kinetic levels (coefficients, or ``Pi2/Pi5`` and ``Pi2``).
    beta : float
        Stribeck transition constant (s/m, or ``Pi6``); 0 gives ``mu_s`` at every speed.
    gamma : float
        Viscous contact constant (s/m, or ``Pi7``).
    normal : float or ndarray
        Normal force ``N`` (units of ``m_EC g`` with coefficients; 1 without vertical motion).

    Returns
    -------
    level, slope : float or ndarray
        ``N (mu_s sech(beta |v|) + mu_k (1 - sech(beta |v|)) + gamma |v|)`` and its derivative
        with respect to ``|v|``.  ``sech`` and ``tanh`` are evaluated from ``exp(-beta |v|)``,
        which cannot overflow.
    """
    av = np.abs(v)
    e = np.exp(-beta * av)
    sech = 2.0 * e / (1.0 + e * e)
    tanh = (1.0 - e * e) / (1.0 + e * e)
    level = mu_s * sech + mu_k * (1.0 - sech) + gamma * av
    slope = -(mu_s - mu_k) * beta * sech * tanh + gamma
    return normal * level, normal * slope
