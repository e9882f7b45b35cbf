"""Module-scoped fixtures of a fragility study's tests: settings, checked study, analyses, dataset."""

import pytest

from isoslide import solver


def study_fixtures(make_settings, module, make_dataset, base: str) -> tuple:
    """The fixtures ``settings``, ``study``, ``analyses`` and ``dataset`` of a fragility test module.

    Parameters
    ----------
    make_settings : callable
        Returns the study's settings (called once per module, after warming up the solver).
    module : module
        The study module: ``check_settings``, ``solve_all`` and ``BASES``.
    make_dataset : callable
        ``(analyses, study, settings, base) -> xarray.Dataset``.
    base : {"isolated", "fixed_base"}
        The base of the ``dataset`` fixture.

    Returns
    -------
    tuple
        The four fixtures, to bind to their names in the test module.
    """
    @pytest.fixture(scope="module")
    def settings():
        solver.warm_up(records=True)
        return make_settings()

    @pytest.fixture(scope="module")
    def study(settings):
        return module.check_settings(settings)

    @pytest.fixture(scope="module")
    def analyses(study):
        return {b: module.solve_all(study, b) for b in module.BASES}

    @pytest.fixture(scope="module")
    def dataset(analyses, study, settings):
        return make_dataset(analyses[base], study, settings, base)

    return settings, study, analyses, dataset
