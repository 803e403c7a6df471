"""The shipped example files are what their builders make."""

import pytest

from polyloops.io.examples import EXAMPLES, example_text
from polyloops.io.formats import dumps


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_shipped_file_matches_builder(name):
    assert example_text(name) == dumps(EXAMPLES[name].build()), "run: python tools/make_examples.py"


def test_examples_named_in_the_spec_are_present():
    spec = {"cube", "box-2x1x1", "l-shape", "ring", "torus-cycle", "degree-two", "double-plus-x",
            "self-crossing"}
    assert spec <= set(EXAMPLES)


def test_box_has_two_x_loops_and_ring_genus_one():
    from polyloops.io.examples import load_example

    assert load_example("box-2x1x1").dualize().axes.count(0) == 2
    assert load_example("ring").genus == 1
