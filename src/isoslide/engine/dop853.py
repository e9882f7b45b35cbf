"""Dormand-Prince 8(5,3) Runge-Kutta tableau (the DOP853 method).

The explicit 12-stage Runge-Kutta pair of order 8 with embedded error
estimators of orders 5 and 3 used by :mod:`isoslide.engine.kernel`.  One step of
length ``h`` from ``(t, y)`` with ``y' = f(t, y)`` evaluates the stages

    k[i] = f(t + C[i] h, y + h sum_j A[i, j] k[j]),   i = 0 .. N_STAGES - 1,

advances with the eighth-order weights, ``y_new = y + h sum_i B[i] k[i]``, and
estimates the local error from the stages plus ``k[N_STAGES] = f(t + h,
y_new)`` (the first stage of the next step) as

    err5 = h sum_i E5[i] k[i],    err3 = h sum_i E3[i] k[i],

combined as ``err5^2 / sqrt(err5^2 + 0.01 err3^2)`` (Hairer et al., II.10).
All coefficients are dimensionless.

Sources
-------
Hairer, E., Norsett, S. P. and Wanner, G., *Solving Ordinary Differential
Equations I: Nonstiff Problems*, 2nd ed., Springer, 1993, Section II.10
(method DOP853), and the published Fortran code ``dop853.f`` by E. Hairer and
G. Wanner (coefficients ``c*``, ``a*``, ``b*``, ``bhh*``, ``er*``).

The literal values below are copied verbatim from SciPy's transcription of
``dop853.f``, ``scipy/integrate/_ivp/dop853_coefficients.py`` (SciPy 1.17.1;
Copyright (c) 2001-2002 Enthought, Inc. and 2003-2024 SciPy Developers;
BSD 3-Clause licence), so the arrays are bit-for-bit those SciPy's ``DOP853``
uses; ``tests/test_kernel.py`` checks that.
"""

from __future__ import annotations

import numpy as np

N_STAGES = 12
"""Stages of one step (the error estimate uses one more, ``f`` at the step end)."""

C = np.array([
    0.0, 0.526001519587677318785587544488e-01, 0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510, 0.281649658092772603273242802490, 0.333333333333333333333333333333,
    0.25, 0.307692307692307692307692307692, 0.651282051282051282051282051282, 0.6,
    0.857142857142857142857142857142, 1.0,
])
"""Nodes ``c``: stage ``i`` is evaluated at ``t + C[i] h`` (shape ``(N_STAGES,)``)."""

_A_ROWS = (
    # A[0, :0] (the first stage is the derivative at the step start)
    (),
    # A[1, :1]
    (
        5.26001519587677318785587544488e-2,
    ),
    # A[2, :2]
    (
        1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2,
    ),
    # A[3, :3]
    (
        2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2,
    ),
    # A[4, :4]
    (
        2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1,
        9.24834003261792003115737966543e-1,
    ),
    # A[5, :5]
    (
        3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
    ),
    # A[6, :6]
    (
        3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2,
        -1.7578125e-2,
    ),
    # A[7, :7]
    (
        3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
    ),
    # A[8, :8]
    (
        6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825,
        -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1, -4.34898841810699588477366255144e1,
    ),
    # A[9, :9]
    (
        4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468,
        -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1, -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
    ),
    # A[10, :10]
    (
        -9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209,
        1.09143734899672957818500254654, -8.14978701074692612513997267357,
        -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1,
        2.49360555267965238987089396762, -3.0467644718982195003823669022,
    ),
    # A[11, :11]
    (
        2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444, -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1, -2.85899827713502369474065508674,
        -8.87285693353062954433549289258, 1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ),
)

A = np.zeros((N_STAGES, N_STAGES))
"""Runge-Kutta matrix ``a`` (strictly lower triangular, shape ``(N_STAGES, N_STAGES)``)."""
for _i, _row in enumerate(_A_ROWS):
    A[_i, :len(_row)] = _row
del _i, _row

B = np.array([
    5.42937341165687622380535766363e-2, 0.0, 0.0, 0.0, 0.0, 4.45031289275240888144113950566,
    1.89151789931450038304281599044, -5.8012039600105847814672114227, 3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1, 2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
])
"""Weights ``b`` of the eighth-order solution (shape ``(N_STAGES,)``)."""

E5 = np.array([
    0.1312004499419488073250102996e-1, 0.0, 0.0, 0.0, 0.0, -0.1225156446376204440720569753e+1,
    -0.4957589496572501915214079952, 0.1664377182454986536961530415e+1, -0.3503288487499736816886487290,
    0.3341791187130174790297318841, 0.8192320648511571246570742613e-1, -0.2235530786388629525884427845e-1,
    0.0,
])
"""Fifth-order error estimator ``er`` (shape ``(N_STAGES + 1,)``; the last stage is ``f`` at the step end)."""

BHH = np.array([
    0.244094488188976377952755905512, 0.733846688281611857341361741547, 0.220588235294117647058823529412e-1,
])
"""Third-order weights ``bhh`` of ``dop853.f``, on stages ``BHH_STAGES``."""

BHH_STAGES = (0, 8, 11)
"""Stages that carry the third-order weights :data:`BHH`."""

E3 = np.append(B, 0.0)
"""Third-order error estimator: ``B`` minus :data:`BHH` on :data:`BHH_STAGES` (shape ``(N_STAGES + 1,)``)."""
for _i, _b in zip(BHH_STAGES, BHH, strict=True):
    E3[_i] -= _b
del _i, _b
