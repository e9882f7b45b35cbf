"""The pipeline configuration: one schema, one source of defaults.

``config/schema.yaml`` (shipped in the package as ``isoslide/data/schema.yaml``)
describes every key of a configuration and gives its default; the workflow
validates ``config/config.yaml`` against it before any job runs
(``snakemake.utils.validate``, which fills the defaults), and :func:`load` does
the same from Python.  Library functions take the completed configuration (or
one of its sections) explicitly and hold no defaults of their own.

Example
-------
>>> import isoslide.config
>>> cfg = isoslide.config.load()                                   # the paper's studies
>>> cfg = isoslide.config.load("config/config.yaml", {"chunk_size": 50})  # doctest: +SKIP
"""

from __future__ import annotations

import copy
import functools
from importlib import resources
from pathlib import Path

import jsonschema
import yaml

SCHEMA_RESOURCE = "data/schema.yaml"
"""Package resource of the configuration schema (``config/schema.yaml``)."""

PAPER_RESOURCE = "data/config.yaml"
"""Package resource of the paper's configuration (``config/config.yaml``)."""


class ConfigError(ValueError):
    """An invalid configuration value; the message names its key path."""


def _read_yaml(path) -> dict:
    with open(path) as f:
        data = yaml.safe_load(f)
    return {} if data is None else data


@functools.lru_cache(maxsize=1)
def _schema_cached() -> dict:
    with resources.as_file(resources.files("isoslide").joinpath(SCHEMA_RESOURCE)) as p:
        return _read_yaml(p)


def schema() -> dict:
    """The configuration schema (a fresh copy)."""
    return copy.deepcopy(_schema_cached())


def paper_config_path() -> Path:
    """Path of the paper's configuration shipped with the package."""
    return Path(str(resources.files("isoslide").joinpath(PAPER_RESOURCE)))


def _default_filling_validator():
    base = jsonschema.Draft202012Validator
    validate_properties = base.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, subschema):
        if isinstance(instance, dict):
            for name, sub in properties.items():
                if "default" in sub:
                    instance.setdefault(name, copy.deepcopy(sub["default"]))
        yield from validate_properties(validator, properties, instance, subschema)

    return jsonschema.validators.extend(base, {"properties": set_defaults})


def validate(config: dict) -> dict:
    """Validate ``config`` against the schema and fill every default (in place); return it.

    Raises
    ------
    ConfigError
        Naming the key path, the offending value and what the schema allows.
    """
    validator = _default_filling_validator()(schema())
    try:
        validator.validate(config)
    except jsonschema.ValidationError as err:
        where = ".".join(str(p) for p in err.absolute_path) or "(top level)"
        raise ConfigError(f"{where}: {err.message}") from None
    return config


def update(base: dict, override: dict) -> dict:
    """Merge ``override`` into ``base`` recursively (dicts merge, other values replace), in place.

    The same rule as Snakemake's ``--configfile`` on top of the workflow's ``configfile``.
    """
    for k, v in override.items():
        if isinstance(v, dict) and isinstance(base.get(k), dict):
            update(base[k], v)
        else:
            base[k] = copy.deepcopy(v)
    return base


def load(path=None, *overrides) -> dict:
    """A complete, validated configuration.

    Parameters
    ----------
    path : str or path-like, optional
        A YAML configuration (default: the paper's, ``config/config.yaml``).
    *overrides : dict or str or path-like
        Configurations merged on top in order (files are read), as Snakemake's
        ``--configfile`` does.

    Returns
    -------
    dict
        Every key of the schema, defaults filled.
    """
    config = _read_yaml(paper_config_path() if path is None else path)
    for extra in overrides:
        update(config, extra if isinstance(extra, dict) else _read_yaml(extra))
    return validate(config)


def defaults() -> dict:
    """Every default of the schema, i.e. the configuration of ``{"studies": {}}`` minus the studies."""
    validator = _default_filling_validator()(schema())
    out: dict = {}
    for _ in validator.iter_errors(out):  # filling happens while validating; "studies" is missing
        pass
    return out
