"""Run the examples in every docstring of the installed ``baranov`` package."""

import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

import baranov.baselines
import baranov.catalog
import baranov.cli
import baranov.closure
import baranov.enumerate
import baranov.explore
import baranov.literature
import baranov.motion
import baranov.planner
import baranov.robots
import baranov.scene
import baranov.solvers
import baranov.topology

MODULES = sorted(
    info.name
    for package in (baranov.topology, baranov.enumerate, baranov.literature, baranov.planner, baranov.closure,
                    baranov.scene, baranov.solvers, baranov.baselines, baranov.catalog, baranov.cli, baranov.robots,
                    baranov.motion, baranov.explore)
    for info in pkgutil.walk_packages(package.__path__, package.__name__ + ".")
    if not info.name.endswith("__main__")
) + ["baranov", "baranov.topology", "baranov.enumerate"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


ROOT = Path(__file__).resolve().parents[1]
PAGES = ["README.md"] + sorted(str(page.relative_to(ROOT)) for page in (ROOT / "docs").glob("*.md")
                               if ">>> " in page.read_text())


@pytest.mark.parametrize("page", PAGES)
def test_documentation_examples(page):
    """The Python examples of README.md and of every docs/ page run as written."""
    result = doctest.testfile(str(ROOT / page), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
