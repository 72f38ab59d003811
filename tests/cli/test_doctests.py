"""The docstring examples of the command line's shared modules (the option parsers, the writer,
the entry point), run here: the package's doctests are collected through pyproject's testpaths,
and this keeps the command line's running without listing its modules there."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = ("crankdyn.cli", "crankdyn.cli.common", "crankdyn.cli.writer")
FLAGS = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=FLAGS, verbose=False, report=True)
    assert result.attempted > 0, f"{name}: no examples"
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed"
