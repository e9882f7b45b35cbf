"""How well the fragility study's floor peaks (PFA, PFV) catch the peak between history rows.

Run: ``python benchmarks/fragility_peaks.py`` (about 10 s).  Three bundled records scaled to
PGA = 6 m/s^2 drive 2e4 kg contents (mu = 0.1 and 0.03) on a slab of 1e6 kg isolated at
T_b = 2.5 s, xi_b = 0.15.  For each, the exact piecewise path's history (one row per record sample
and transition) is compared with the integrator's history about every 0.15 ms (150,000 rows):
the relative error of the largest row alone, and of :func:`isoslide.studies.intensity.floor_peaks`
(cubic Hermite between rows with the floor jerk), against the dense history's peak.
"""

import numpy as np

from isoslide import solver
from isoslide.records import sample
from isoslide.scene import Scene
from isoslide.store.history_io import history_table
from isoslide.studies import fragility_study as fs
from isoslide.studies.intensity import floor_peaks


def main() -> None:
    solver.warm_up(records=True)
    print(f"{'record':26s} {'mu':>5s} {'model':20s} {'PFA rows only':>14s} {'PFA':>10s} {'PFV':>10s}")
    for name in ("Northridge_1994_PAC-175", "Coyote_Lake_1979_G02-050", "Kobe_1995_TAK-090"):
        rec = sample(name)
        pulse, pga, _ = fs.scaled_pulse(rec, "pga", 6.0)
        for mu in (0.1, 0.03):
            scene = Scene.from_physical(a_p=pga, T_p=1.0, M_b=1e6, T_b=2.5, xi_b=0.15, m_ec=2e4, mu_s=mu, mu_k=mu,
                                        pulse=pulse)
            exact = solver.solve(scene, history=True)
            dense = solver.solve(scene, history=True, max_step=rec.duration * 1.1 / 150000, rtol=1e-10)
            rows = np.max(np.abs(history_table(exact, scene).columns["floor_accel"]))
            (a1, v1), (a2, v2) = floor_peaks(exact, scene), floor_peaks(dense, scene)
            print(f"{name:26s} {mu:5.2f} {exact.model:20s} {rows / a2 - 1:14.1e} {a1 / a2 - 1:10.1e} {v1 / v2 - 1:10.1e}")


if __name__ == "__main__":
    main()
