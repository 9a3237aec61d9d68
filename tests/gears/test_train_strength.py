"""The gear-train type by hand: every refusal's sentence, the axis paths and carriers, the text and JSON forms,
the nauty graphs of the displacement and rotation graphs, symmetry and the split of the Willis equations."""

from __future__ import annotations

import pytest

from synth.errors import MalformedChain
from synth.gears import GearTrain
from synth.gears.train import axis_paths, fractionated, rotation_graph
from synth.structure.chain import Chain

SIMPLE = GearTrain.parse("0-1-2 2-3 0~3i 1~3")  # ring 0, sun 1, carrier 2, planet 3
TWO_PLANETS = GearTrain.parse("0-1 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1")  # ring 0, carrier 1, floating sun 2

_FORMS = "write axes as '0-1-2' and meshes as '1~3', '0~3i' (internal, ring first) or '2~3@1' (carrier 1)"


@pytest.mark.parametrize("make,sentence", [
    (lambda: GearTrain(1, [], []), "a gear train needs a whole number of links ≥ 2, not 1"),
    (lambda: GearTrain(True, [], []), "a gear train needs a whole number of links ≥ 2, not True"),
    (lambda: GearTrain(3.0, [], []), "a gear train needs a whole number of links ≥ 2, not 3.0"),
    (lambda: GearTrain(4, [("a", 1)], []), "axes and meshes must be lists of link numbers"),
    (lambda: GearTrain(4, [(0, 1)], [None]), "axes and meshes must be lists of link numbers"),
    (lambda: GearTrain(4, [(0,)], []), "axis [0] must join two or more different links"),
    (lambda: GearTrain(4, [(0, 0)], []), "axis [0, 0] must join two or more different links"),
    (lambda: GearTrain(4, [(0, 4)], []), "axis [0, 4] names a link outside 0…3"),
    (lambda: GearTrain(4, [(-1, 2)], []), "axis [-1, 2] names a link outside 0…3"),
    (lambda: GearTrain(4, [(0, 1), (1, 0)], []), "two axes join the same links: write them as one axis"),
    (lambda: GearTrain(4, [(0, 1)], [(1, 1)]), "mesh [1, 1] must join two different links of 0…3"),
    (lambda: GearTrain(4, [(0, 1)], [(1, 4)]), "mesh [1, 4] must join two different links of 0…3"),
    (lambda: GearTrain(4, [(0, 1)], [(-1, 2)]), "mesh [-1, 2] must join two different links of 0…3"),
    (lambda: GearTrain(4, [(0, 1)], [(1, 2, 3)]), "mesh [1, 2, 3] must join two different links of 0…3"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], internal=[True, False]), "2 mesh kinds given for 1 meshes"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], carriers=[1, 1]), "2 carriers given for 1 meshes"),
    (lambda: GearTrain(4, [(0, 1), (2, 3)], [(0, 2)]),
     "mesh 0~2 has no carrier: its gears must turn on one link about two different axes "
     "(a – axis – carrier – axis – b); give the carrier as 0~2@t"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], carriers=[0]),
     "the carrier of mesh 0~2 must be a third link of 0…3, not 0"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], carriers=[4]),
     "the carrier of mesh 0~2 must be a third link of 0…3, not 4"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], carriers=[-1]),
     "the carrier of mesh 0~2 must be a third link of 0…3, not -1"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2), (2, 0)]), "two meshes join the same two links: a pair of gears meshes once"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], frame=4), "the frame 4 is not a link of 0…3"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], frame=-1), "the frame -1 is not a link of 0…3"),
    (lambda: GearTrain(4, [(0, 1), (1, 2)], [(0, 2)], frame=True), "the frame True is not a link of 0…3"),
    (lambda: GearTrain.parse("{bad"), "gear train JSON is not valid JSON: Expecting property name enclosed in double "
                                      "quotes at position 1"),
    (lambda: GearTrain.parse("0-x 1~2"), f"cannot read '0-x': {_FORMS}"),
    (lambda: GearTrain.parse("0-1, 1~a"), f"cannot read '1~a': {_FORMS}"),
    (lambda: GearTrain.parse("   "), "an empty text is not a gear train"),
    (lambda: GearTrain.parse("0-1 2~3@1 0~3"), "mesh 0~3 has no carrier: give it as 0~3@t"),
    (lambda: GearTrain.from_chain(Chain.parse("0-1 1=2 2-0")), "a gear train turns on axes and meshes: it has no prismatic pair"),
    (lambda: GearTrain.from_dict([]), "a gear train object needs 'axes' and 'meshes' (or 'train', its text form)"),
    (lambda: GearTrain.from_dict({"axes": []}), "a gear train object needs 'axes' and 'meshes' (or 'train', its text form)"),
    (lambda: GearTrain.from_dict({"axes": [], "meshes": []}),
     "the gear train object has no axes and no meshes: give each axis as the links that turn about it and each mesh "
     "as its two gears"),
    (lambda: GearTrain.from_dict({"axes": [], "meshes": [], "links": 3}),
     "the gear train object has no axes and no meshes: give each axis as the links that turn about it and each mesh "
     "as its two gears"),
    (lambda: GearTrain.from_dict({"axes": 5, "meshes": []}), "axes and meshes must be lists of link numbers"),
    (lambda: GearTrain.from_dict({"axes": [[0, 1]], "meshes": [[1, None]]}), "axes and meshes must be lists of link numbers"),
    # every link turns on an axis or meshes (a carrier too), and the axes and meshes join them all
    (lambda: GearTrain.parse("0-1 0~3@1"),
     "link 2 is in no axis and no mesh: every link of a gear train turns on an axis or meshes"),
    (lambda: GearTrain.parse("0-1 1~2@3"),
     "link 3 is in no axis and no mesh: every link of a gear train turns on an axis or meshes"),
    (lambda: GearTrain.from_dict({"axes": [[0, 1]], "meshes": [[0, 3]], "carriers": [1]}),
     "link 2 is in no axis and no mesh: every link of a gear train turns on an axis or meshes"),
    (lambda: GearTrain.from_dict({"axes": [[0, 1]], "meshes": [], "links": 9}),
     "links 2, 3, 4, 5, 6, … are in no axis and no mesh: every link of a gear train turns on an axis or meshes"),
    (lambda: GearTrain.parse("0-1 2-3"),
     "links 2, 3 are not joined to link 0 by axes and meshes: a gear train is one connected set of links"),
    (lambda: GearTrain.parse("0-1 2~3@0"),
     "links 2, 3 are not joined to link 0 by axes and meshes: a gear train is one connected set of links"),
    (lambda: GearTrain(5, [(0, 1), (1, 2), (3, 4)], [(0, 2)], carriers=[1]),
     "links 3, 4 are not joined to link 0 by axes and meshes: a gear train is one connected set of links"),
])
def test_every_refusal_in_full(make, sentence):
    with pytest.raises(MalformedChain) as refused:
        make()
    assert str(refused.value) == sentence


def test_axis_paths_alternate_links_and_axes():
    """Axes 0 = (0, 1, 2) and 1 = (2, 3): from planet 3 one reaches the carrier 2 by axis 1, then 0 and 1 by axis 0."""
    assert axis_paths(4, [(0, 1, 2), (2, 3)])[3] == {3: [3], 2: [3, 1, 2], 0: [3, 1, 2, 0, 0], 1: [3, 1, 2, 0, 1]}
    assert axis_paths(3, [(0, 1)])[2] == {2: [2]}  # a link on no axis reaches nothing


def test_carriers_are_the_middle_links_of_the_axis_paths():
    """Ring 0 – axis – carrier 2 – axis – planet 3: both meshes of the simple train are held by the carrier;
    a carrier found from the axes is not written, one given against them is (``@t``)."""
    assert SIMPLE.carriers == (2, 2) and SIMPLE.triples == ((0, 3, 2), (1, 3, 2))
    assert TWO_PLANETS.carriers == (1, 1, 1, 1)
    assert TWO_PLANETS.compact() == "0-1 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1"
    assert GearTrain.parse("0-1-2 2-3 3~1 0~3i").compact() == "0-1-2 2-3 0~3i 1~3"  # external meshes in order


def test_text_json_and_chain_forms_round_trip():
    row = TWO_PLANETS.to_dict()
    assert {k: row[k] for k in ("train", "links", "axes", "meshes", "carriers", "dof", "code", "internal")} == {
        "train": "0-1 1-3 1-4 0~3i 0~4i 2~3@1 2~4@1", "links": 5, "axes": [[0, 1], [1, 3], [1, 4]],
        "meshes": [[0, 3], [0, 4], [2, 3], [2, 4]], "carriers": [1, 1, 1, 1], "dof": 12 - 6 - 4, "code": "540/0",
        "internal": [True, True, False, False]}
    assert row["certificate"] == TWO_PLANETS.certificate and row["rotation_certificate"] == TWO_PLANETS.rotation_certificate
    assert "frame" not in row and "internal" not in GearTrain.parse("0-1 1-2 0~2").to_dict()
    assert GearTrain.from_dict(row) == TWO_PLANETS == GearTrain.parse(TWO_PLANETS.to_json())
    framed = GearTrain.parse(SIMPLE.compact(), frame=0)
    assert framed.to_dict()["frame"] == 0 and GearTrain.from_dict(framed.to_dict()) == framed
    assert GearTrain.from_dict({"train": "0-1-2 2-3 0~3i 1~3", "frame": 2}) == GearTrain.parse(SIMPLE.compact(), 2)
    no_links = GearTrain.from_dict({"axes": [[0, 1, 2], [2, 3]], "meshes": [[0, 3], [1, 3]], "internal": [True, False]})
    assert no_links == SIMPLE and no_links.links == 4
    chain = SIMPLE.to_chain()
    assert chain.compact() == "0-1-2 0~3 1~3 2-3" and GearTrain.from_chain(chain).meshes == SIMPLE.meshes
    assert GearTrain.from_chain(chain).axes == SIMPLE.axes and GearTrain.from_chain(chain).carriers == (2, 2)


def test_the_rotation_graph_by_hand():
    """Links 0 … 3, a node per mesh (4, 5) joined to its gears and to a node per carrier role (6, 7) joined to
    the carrier: three colours."""
    g = rotation_graph(4, [(0, 3, 2), (1, 3, 2)])
    assert g.number_of_vertices == 8 and g.adjacency_dict == {4: [0, 3, 6], 6: [2], 5: [1, 3, 7], 7: [2]}
    assert g.vertex_coloring == [{0, 1, 2, 3}, {4, 5}, {6, 7}]


def test_the_displacement_graph_by_hand():
    """Axes (4, 5) joined to their links, meshes (6, 7) to their gears; the internal mesh 6 in a colour of its
    own and a tag node 8 on it and its ring 0; marked links first, each alone."""
    g = SIMPLE._graph()
    assert g.adjacency_dict == {4: [0, 1, 2], 5: [2, 3], 6: [0, 3], 7: [1, 3], 8: [0, 6]}
    assert g.vertex_coloring == [{0, 1, 2, 3}, {4, 5}, {7}, {6}, {8}]
    assert SIMPLE._graph(marked=(0, 2)).vertex_coloring == [{0}, {2}, {1, 3}, {4, 5}, {7}, {6}, {8}]
    plain = GearTrain.parse("0-1-2 2-3 0~3 1~3")
    assert plain._graph().adjacency_dict == {4: [0, 1, 2], 5: [2, 3], 6: [0, 3], 7: [1, 3]}
    assert plain._graph().vertex_coloring == [{0, 1, 2, 3}, {4, 5}, {6, 7}, set()]


def test_symmetry_and_certificates():
    """The two planets swap; fixing one leaves no symmetry.  A ring told from an external wheel, and a frame,
    change the certificate; a renumbering does not."""
    assert TWO_PLANETS.automorphisms() == ([[0, 1, 2, 4, 3]], [0, 1, 2, 3, 3])
    assert TWO_PLANETS.automorphisms(marked=(3,)) == ([], [0, 1, 2, 3, 4])
    renumbered = GearTrain.parse("4-1 1-3 1-0 4~3i 4~0i 2~3@1 2~0@1")
    assert renumbered.certificate == TWO_PLANETS.certificate
    assert GearTrain.parse("0-1 1-3 1-4 0~3 0~4 2~3@1 2~4@1").certificate != TWO_PLANETS.certificate
    assert GearTrain.parse(TWO_PLANETS.compact(), frame=0).certificate != TWO_PLANETS.certificate
    assert GearTrain.parse(TWO_PLANETS.compact(), frame=0).certificate != GearTrain.parse(TWO_PLANETS.compact(), frame=2).certificate
    assert renumbered.rotation_certificate == TWO_PLANETS.rotation_certificate
    assert SIMPLE.rotation_certificate != TWO_PLANETS.rotation_certificate


@pytest.mark.parametrize("links,triples,split", [
    (5, [(1, 2, 0), (3, 4, 0)], True),  # two pairs on one frame: link 0 cuts them apart
    (4, [(0, 3, 2), (1, 3, 2)], False),  # the simple train
    (4, [(0, 1, 2)], True),  # link 3 in no mesh and carrying none
    (2, [], True),  # no mesh at all: not connected
    (3, [(0, 1, 2)], False),  # one mesh and its carrier: a triangle
    (6, [(0, 1, 2), (3, 4, 5)], True),  # two trains apart
    (5, [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)], False),  # four meshes round one carrier
])
def test_fractionation_by_hand(links, triples, split):
    assert fractionated(links, triples) is split
