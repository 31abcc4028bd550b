"""The examples in the docstrings run and print what they say (SciPy-style docstrings are
read by users in a notebook: a wrong example there is a wrong answer)."""

from __future__ import annotations

import doctest
import importlib

import pytest

from conftest import package_modules

MODULES = sorted(
    name
    for name, path in package_modules().items()
    if path.name != "__main__.py"  # runs the command line when imported
)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # an example that writes a file writes it here
    module = importlib.import_module(name)
    result = doctest.testmod(
        module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False
    )
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed"


def test_the_examples_are_many():
    """Not vacuous: the package's docstrings hold examples (cummins, fit_radiation, …)."""
    finder = doctest.DocTestFinder()
    count = sum(
        len(t.examples) for t in finder.find(importlib.import_module("cummins.radiation.fit"))
    )
    assert count >= 3
