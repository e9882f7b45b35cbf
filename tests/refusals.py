"""How the tests check that bad settings are refused."""

import pytest


def assert_refused(check, settings, match: str) -> None:
    """``check(settings)`` raises a ValueError whose message matches ``match`` and says what is allowed.

    Parameters
    ----------
    check : callable
        The settings check (``check_settings`` of a study).
    settings : dict
        The bad settings.
    match : str
        Regular expression the message must match (the key and its value).
    """
    with pytest.raises(ValueError, match=match) as err:
        check(settings)
    assert "allowed" in str(err.value)
