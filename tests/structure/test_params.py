"""The parameters every query shares (W, h, f): the values allowed, each refusal's sentence."""

from __future__ import annotations

import pytest

from synth.errors import ImpossibleParameters, InvalidOption
from synth.structure._params import H_MAX, check_dof, check_extra_mobility, check_motion_space


def test_the_values_allowed_come_back():
    assert [check_dof(w) for w in (0, 1, 7)] == [0, 1, 7]
    assert [check_extra_mobility(f) for f in (0, 2)] == [0, 2]
    assert [check_motion_space(h) for h in range(1, 7)] == [1, 2, 3, 4, 5, 6] and H_MAX == 6
    assert check_motion_space(2, lowest=2) == 2


@pytest.mark.parametrize("check, value, error, sentence", [
    (check_dof, -1, ImpossibleParameters, "the degree of freedom W must be 0 or more, not -1"),
    (check_dof, 1.5, InvalidOption, "the degree of freedom W must be a whole number, not 1.5"),
    (check_dof, True, InvalidOption, "the degree of freedom W must be a whole number, not True"),
    (check_extra_mobility, -2, ImpossibleParameters, "the extra pair mobility f must be 0 or more, not -2"),
    (check_extra_mobility, "1", InvalidOption, "the extra pair mobility f must be a whole number, not '1'"),
    (check_motion_space, 0, ImpossibleParameters, "the motion space h of a loop is 1 … 6 (6: general spatial loop), "
                                                  "not 0"),
    (check_motion_space, 7, ImpossibleParameters, "the motion space h of a loop is 1 … 6 (6: general spatial loop), "
                                                  "not 7"),
    (check_motion_space, 3.0, InvalidOption, "the motion space h must be a whole number, not 3.0"),
])
def test_each_refusal_is_its_sentence(check, value, error, sentence):
    with pytest.raises(error) as info:
        check(value)
    assert str(info.value) == sentence


def test_a_lowest_motion_space():
    with pytest.raises(ImpossibleParameters) as info:
        check_motion_space(1, lowest=2)
    assert str(info.value) == "the motion space h of a loop is 2 … 6 (6: general spatial loop), not 1"
