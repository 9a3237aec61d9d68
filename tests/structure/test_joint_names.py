"""A joint named by its links is read in one place (``Chain.joint_index``) and refused in one sentence,
whether the name comes from a linkage file, a scene or the command line."""

from __future__ import annotations

import pytest

from mechsynth import cli
from synth import Chain, Linkage, MotionError, UnknownJoint

WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
TRIPLE = Chain.parse("0-1-2 1-3 2-3")


def test_every_way_of_writing_a_joint_names_the_same_joint():
    for k, links in enumerate(WATT.joints):
        a, b = links
        names = [f"{a}-{b}", f"{b}-{a}", f"{a}={b}", f"{b}~{a}", f" {a} - {b} ", [a, b], (b, a), k]
        assert {WATT.joint_index(name) for name in names} == {k}
    assert TRIPLE.joint_index("2-0-1") == TRIPLE.joints.index((0, 1, 2))


@pytest.mark.parametrize("name, words", [
    (7, "--input names joint 7, but the chain has joints 0 … 6"),
    (-1, "--input names joint -1, but the chain has joints 0 … 6"),
    (True, "--input names joint True: write a joint by its links, e.g. '1-2'"),
    ("1-x", "--input names joint '1-x': write a joint by its links, e.g. '1-2'"),
    ("", "--input names joint '': write a joint by its links, e.g. '1-2'"),
    (None, "--input names joint None: write a joint by its links, e.g. '1-2'"),
    ("0-2", "--input names joint '0-2', which is not a joint of the chain 0-1 0-3 0-4 1-2 1-5 2-3 4-5"),
    ("0-1-2", "--input names joint '0-1-2', which is not a joint of the chain 0-1 0-3 0-4 1-2 1-5 2-3 4-5"),
])
def test_a_name_that_is_no_joint_is_refused_in_one_sentence(name, words):
    with pytest.raises(UnknownJoint) as info:
        WATT.joint_index(name, "--input")
    assert str(info.value) == words


def test_the_linkage_file_and_the_command_line_say_the_same_sentence(capsys):
    points = {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3.5, 3], "0-3": [4, 0]}
    with pytest.raises(MotionError) as info:
        Linkage.from_dict({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["1-x"], "points": points})
    assert str(info.value) == "'inputs' names joint '1-x': write a joint by its links, e.g. '1-2'"
    assert cli.main(["move", "--chain", "0-1 1-2 2-3 3-0", "--frame", "0", "--input", "1-x"]) == 2
    assert capsys.readouterr().err == "mechsynth: --input names joint '1-x': write a joint by its links, e.g. '1-2'\n"
