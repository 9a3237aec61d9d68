"""The elementary edits of a chain by hand: a binary link removed with its joints, a multiple joint split."""

from __future__ import annotations

from synth import Chain
from synth.analysis.repair import chain_edits


def test_a_binary_link_of_a_four_bar_is_removed_with_its_joints():
    """Link 0 of the four-bar goes with its pins 0-1 and 0-3: links 1, 2, 3 (renumbered 0, 1, 2) joined 1-2, 2-3."""
    edits = dict(chain_edits(Chain.parse("0-1 1-2 2-3 3-0")))
    assert edits["remove the binary link 0 with its joints 0-1 and 0-3"] == Chain.parse("0-1 1-2")


def test_a_double_joint_is_split_into_two_pins():
    """0-1-2 joins three links: split, it leaves 1-2 and a pin from the link taken out to link 1."""
    chain = Chain.parse("0-1-2 2-3 3-4 4-0 1-5 5-4")
    edits = dict(chain_edits(chain))
    split = edits["split joint 0-1-2 into 1-2 and 0-1"]
    assert split == Chain.parse("0-1 1-2 2-3 3-4 4-0 1-5 5-4") and (split.v, split.links) == (0, 6)
    assert sum(w.startswith("split joint 0-1-2") for w in edits) == 3
