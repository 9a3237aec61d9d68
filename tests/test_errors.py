"""Options named in error messages: the command line's spelling and a Python caller's."""

from __future__ import annotations

from synth.errors import InvalidOption, flag, option


def test_an_option_is_spelled_for_its_reader():
    assert flag("rigid_subchains", "True") == "--rigid-subchains"
    assert flag("max_link_degree", "5") == "--max-link-degree 5"
    error = InvalidOption(f"give {option('rigid_subchains')} or {option('max_link_degree', '5')}")
    assert str(error) == "give rigid_subchains=True or max_link_degree=5"
    assert error.text(flag) == "give --rigid-subchains or --max-link-degree 5"
