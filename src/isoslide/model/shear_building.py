"""A shear building on a held slab: storey stiffness matrix, fixed-base modes, classical damping.

Floor ``j`` (1-based, bottom to top) has the mass ``m_j``; storey ``j`` joins floor ``j - 1``
(0 the slab, held) and floor ``j`` with the stiffness ``k_j``.  The fixed-base stiffness matrix
``Ks`` acts on the floors' displacements relative to the slab; the damping matrix with the ratio
``xi`` in every fixed-base mode is ``Cs = Ms Phi diag(2 xi omega_i) Phi^T Ms`` with the
mass-normalised modes ``Phi`` (``Phi^T Ms Phi = I``).  Any consistent units; the functions are
used in SI units by :meth:`isoslide.Scene.from_physical` and in the model's units by
:func:`isoslide.engine.building.superstructure`.
"""

from __future__ import annotations

import numpy as np


def stiffness_matrix(k) -> np.ndarray:
    """Fixed-base stiffness matrix ``(N, N)`` of a shear chain of storey stiffnesses ``k`` (bottom to top)."""
    k = np.asarray(k, dtype=float)
    above = np.append(k[1:], 0.0)      # storey j + 1 joins floor j (0 the slab) and floor j + 1
    return np.diag(k + above) - np.diag(k[1:], 1) - np.diag(k[1:], -1)


def fixed_base_modes(masses, K) -> tuple:
    """Circular frequencies (ascending) and mass-normalised mode shapes of ``Ms^-1 K``.

    Parameters
    ----------
    masses : array_like, shape (N,)
        Floor masses.
    K : ndarray, shape (N, N)
        Fixed-base stiffness matrix.

    Returns
    -------
    omega : ndarray, shape (N,)
        ``omega_i`` (rad per unit time), ascending.
    phi : ndarray, shape (N, N)
        Columns: the modes, with ``phi^T Ms phi = I``.
    """
    masses = np.asarray(masses, dtype=float)
    s = 1.0 / np.sqrt(masses)
    lam, V = np.linalg.eigh(K * s[:, None] * s[None, :])
    return np.sqrt(lam), V * s[:, None]


def classical_damping(masses, omega, phi, xi: float) -> np.ndarray:
    """Damping matrix with the ratio ``xi`` in every mode, ``Ms phi diag(2 xi omega) phi^T Ms`` (symmetric)."""
    mphi = np.asarray(masses, dtype=float)[:, None] * phi
    C = (mphi * (2.0 * xi * omega)[None, :]) @ mphi.T
    return 0.5 * (C + C.T)


def fundamental_period(masses, k) -> float:
    """Fixed-base fundamental period ``2 pi / omega_1`` of floor masses ``masses`` and storey stiffnesses ``k``."""
    omega, _ = fixed_base_modes(masses, stiffness_matrix(k))
    return 2.0 * np.pi / omega[0]
