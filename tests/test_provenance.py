"""isoslide.store.provenance: code hashes by module name, the source text and job logs.

Edits happen in a temporary copy of the package sources, never in the package itself.
"""

import logging
import re
import shutil
import warnings

import pytest

from isoslide import datasets
from isoslide.store import provenance


@pytest.fixture
def pkg(tmp_path):
    """A copy of the package's sources (``isoslide/`` without caches or data)."""
    dest = tmp_path / "copy" / "isoslide"
    shutil.copytree(provenance.PACKAGE_DIR, dest,
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc", "data"))
    return dest


def _edit(path):
    path.write_text(path.read_text() + "\n# edited\n")


def _toy_package(root, records_as_package):
    root.mkdir(parents=True)
    (root / "__init__.py").write_text("")
    (root / "solver.py").write_text("x = 1\n")
    (root / "peers").mkdir()
    (root / "peers" / "__init__.py").write_text("from . import reference\n")
    (root / "peers" / "reference.py").write_text("y = 2\n")
    if records_as_package:
        (root / "records").mkdir()
        (root / "records" / "__init__.py").write_text("")
        (root / "records" / "reading.py").write_text("def read_at2(): ...\n")
    else:
        (root / "records.py").write_text("def read_at2(): ...\n")
    return root


def test_a_module_name_is_one_file_and_a_subpackage_name_all_of_its_files(tmp_path):
    root = _toy_package(tmp_path / "isoslide", records_as_package=True)
    assert provenance.module_files("solver", root) == [root / "solver.py"]
    assert provenance.module_files("peers.reference", root) == [root / "peers" / "reference.py"]
    assert provenance.module_files("peers", root) == [root / "peers" / "__init__.py",
                                                      root / "peers" / "reference.py"]
    assert provenance.module_files("records", root) == [root / "records" / "__init__.py",
                                                        root / "records" / "reading.py"]


def test_records_hash_whether_a_module_or_a_subpackage(tmp_path):
    as_module = _toy_package(tmp_path / "a" / "isoslide", records_as_package=False)
    as_package = _toy_package(tmp_path / "b" / "isoslide", records_as_package=True)
    assert provenance.module_files("records", as_module) == [as_module / "records.py"]
    h_module = provenance.code_hash(["records"], package_dir=as_module)
    h_package = provenance.code_hash(["records"], package_dir=as_package)
    assert h_module != h_package      # moving code into a subpackage is a change of the code
    assert provenance.code_hash(["solver"], package_dir=as_module) == \
        provenance.code_hash(["solver"], package_dir=as_package)


@pytest.mark.parametrize("name", ["no_such_module", "peers.no_such_module", "solver.kernel", "", "peers..x",
                                  "../setup"])
def test_an_unknown_module_name_raises_naming_it(pkg, name):
    with pytest.raises(ValueError, match="no module|not a module name"):
        provenance.code_hash(["solver", name], package_dir=pkg)
    with pytest.raises(ValueError, match="no module|not a module name"):
        provenance.code_hash(exclude=[name], package_dir=pkg)


def test_a_single_string_is_not_taken_for_a_list_of_names(pkg):
    with pytest.raises(TypeError, match="collection of module names"):
        provenance.code_hash("solver", package_dir=pkg)


def test_the_hash_follows_exactly_the_listed_files(pkg):
    solver = ["solver", "engine.kernel", "pulses", "scene"]
    records = ["records"]
    before = {name: provenance.code_hash(mods, package_dir=pkg)
              for name, mods in (("solver", solver), ("records", records), ("peer", ["peers.reference"]),
                                 ("peers", ["peers"]), ("all", None))}

    reader = sorted(provenance.module_files("records", pkg))[-1]
    _edit(reader)                                                 # a records module (the record reader)
    after = {name: provenance.code_hash(mods, package_dir=pkg)
             for name, mods in (("solver", solver), ("records", records), ("peer", ["peers.reference"]),
                                ("peers", ["peers"]), ("all", None))}
    assert after["solver"] == before["solver"] and after["peer"] == before["peer"]
    assert after["peers"] == before["peers"]
    assert after["records"] != before["records"] and after["all"] != before["all"]

    _edit(pkg / "engine" / "kernel.py")
    assert provenance.code_hash(solver, package_dir=pkg) != before["solver"]
    assert provenance.code_hash(records, package_dir=pkg) == after["records"]

    _edit(pkg / "peers" / "reference.py")
    assert provenance.code_hash(["peers.reference"], package_dir=pkg) != before["peer"]
    assert provenance.code_hash(["peers"], package_dir=pkg) != before["peers"]


def test_a_new_file_in_a_subpackage_changes_its_hash(pkg):
    before = provenance.code_hash(["peers"], package_dir=pkg)
    (pkg / "peers" / "another.py").write_text("z = 3\n")
    assert provenance.code_hash(["peers"], package_dir=pkg) != before
    assert provenance.code_hash(["peers"], exclude=["peers.another"], package_dir=pkg) == before


def test_the_hash_does_not_depend_on_where_the_package_lives_or_the_order_of_names(pkg, tmp_path):
    other = tmp_path / "elsewhere" / "isoslide"
    shutil.copytree(pkg, other)
    names = ["solver", "peers", "records", "engine.kernel"]
    assert provenance.code_hash(names, package_dir=pkg) == provenance.code_hash(names[::-1], package_dir=other)
    assert provenance.code_hash(names + ["solver"], package_dir=pkg) == provenance.code_hash(names, package_dir=pkg)


def test_moving_code_between_modules_changes_the_hash(tmp_path):
    a = _toy_package(tmp_path / "a" / "isoslide", records_as_package=True)
    b = _toy_package(tmp_path / "b" / "isoslide", records_as_package=True)
    text = (b / "records" / "reading.py").read_text()
    (b / "records" / "reading.py").write_text("")
    (b / "records" / "__init__.py").write_text(text)
    assert provenance.code_hash(["records"], package_dir=a) != provenance.code_hash(["records"], package_dir=b)


def test_datasets_uses_the_provenance_functions():
    assert datasets.code_hash is provenance.code_hash
    assert datasets.git_commit is provenance.git_commit
    assert datasets.global_attrs("t", "h")["source"] == provenance.source_text()
    assert provenance.source_text().startswith("isoslide ")


def test_log_to_writes_records_and_the_traceback_then_lets_go(tmp_path):
    log = tmp_path / "logs" / "rule" / "job.log"
    with pytest.raises(ZeroDivisionError):
        with provenance.log_to(log) as job:
            job.info("solving %d scenes", 12)
            logging.getLogger("isoslide.studies.sweep").info("from the library")
            logging.getLogger("isoslide.studies.sweep").debug("too detailed")
            warnings.warn("a warning from the job", UserWarning, stacklevel=1)
            1 / 0  # noqa: B018
    text = log.read_text()
    assert provenance.source_text() in text.splitlines()[0]
    assert "solving 12 scenes" in text and "from the library" in text and "too detailed" not in text
    assert "a warning from the job" in text
    assert "Traceback" in text and "ZeroDivisionError" in text
    assert not text.rstrip().endswith("done")

    logging.getLogger("isoslide.studies.sweep").warning("after the job")      # the handler is gone
    assert "after the job" not in log.read_text()


def test_log_to_ends_a_successful_job_with_done(tmp_path):
    log = tmp_path / "job.log"
    with provenance.log_to(log) as job:
        job.info("working")
    lines = log.read_text().splitlines()
    assert len(lines) == 4 and lines[2].endswith("working") and lines[-1].endswith("done")
    assert re.search(r"isoslide\.job: phase start-up \d+\.\d{3} s$", lines[1]), lines[1]
    with provenance.log_to(log):
        pass
    assert "working" not in log.read_text()                          # a rerun starts the log afresh
