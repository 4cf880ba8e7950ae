"""The top-level API (``import baranov``) and names: every name the catalog identifies
resolves, from any folder."""

import subprocess
import sys

import pytest

import baranov
from baranov.catalog import CATALOG_FOLDER, load_entries
from baranov.enumerate import baranov_trusses
from baranov.topology import are_isomorphic

THESIS_NAMES = ["3/B1", "5/B1", "7/B1", "7/B2", "7/B3", *(f"9/B{k}" for k in range(1, 29))]


def test_import_is_lazy_and_lists_the_api():
    """``import baranov`` loads no solver; every name of ``__all__`` resolves."""
    code = ("import sys, baranov; assert 'baranov.solvers' not in sys.modules, 'eager'; "
            "print(all(getattr(baranov, name) is not None for name in baranov.__all__))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "True"
    assert {"truss", "solve", "load_scene", "best_plan", "closure_system", "characteristic_degree"} <= set(dir(baranov))


def test_unknown_attribute_is_an_attribute_error():
    with pytest.raises(AttributeError, match="has no attribute 'solver'"):
        baranov.solver  # noqa: B018


@pytest.mark.parametrize("name", THESIS_NAMES)
def test_every_thesis_name_resolves_to_its_catalog_truss(name):
    """Thesis names come from the literature module (3/B1 … 7/B3, 9/B28) or from the
    catalog's evidence (9/B1 … 9/B27); either way the truss is the catalog's."""
    links = int(name.split("/")[0])
    entries = {e["name"]: e for e in load_entries(CATALOG_FOLDER / f"trusses-{links}.jsonl")}
    chain = baranov.truss(name)
    identifier = entries[name]["id"]
    assert are_isomorphic(chain, baranov_trusses(links)[int(identifier.split("N")[1]) - 1])


@pytest.mark.parametrize("name", ["7/N3", "9/N28", "11/N1"])
def test_ids_resolve(name):
    links, index = int(name.split("/")[0]), int(name.split("N")[1])
    assert are_isomorphic(baranov.truss(name), baranov_trusses(links)[index - 1])


@pytest.mark.parametrize("name, message", [
    ("9/B29", "9/B29: no such truss in the catalog (names 9/B1, 9/B2, 9/B3 …; ids 9/N1..9/N28)"),
    ("8/N1", "8/N1: no such truss in the catalog (it has no 8-link trusses"),
    ("B1", "B1: several thesis trusses have this name: 3/B1, 5/B1, 7/B1, 9/B1"),
    ("B29", "B29: not a truss name (expected e.g. 9/B28 or 11/N123)"),
])
def test_unknown_names_say_what_exists(name, message):
    with pytest.raises(baranov.TrussNameError) as error:
        baranov.truss(name)
    assert str(error.value).startswith(message)


def test_version_and_fast_help(tmp_path):
    result = subprocess.run([sys.executable, "-m", "baranov.cli", "--version"], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0 and result.stdout.strip() == f"baranov {baranov.__version__}"
    code = "import sys, baranov.cli.main; print(sorted(m for m in ('numpy', 'sympy', 'flint') if m in sys.modules))"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "[]"
