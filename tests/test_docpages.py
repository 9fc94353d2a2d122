"""The docs pages' comparison of printed output (tests/docpages.py): numbers up to their
rounding, everything else exactly."""

from __future__ import annotations

from tests.docpages import last_place, same_text, same_token


def test_last_place_is_one_unit_of_the_last_printed_digit() -> None:
    assert last_place("0.0123") == 1e-4
    assert last_place("1.5e-08") == 1e-9
    assert last_place("120") == 1
    assert last_place("-7.08194718886e-09") == 1e-20


def test_numbers_match_up_to_their_rounding() -> None:
    # the fit's k2 as printed on two machines: 12 significant digits, BLAS rounding
    assert same_token("3.2541818864e-08", "3.25418188644e-08")
    # one unit of the shown last digit either way is rounding
    assert same_token("0.9806", "0.9805") and same_token("0.9806", "0.9807")
    # two units is a change
    assert not same_token("0.9806", "0.9804")
    # a relative change of 1e-6 in a full-precision number is a change
    assert not same_token("0.00010931985368111099", "0.00010932")
    assert not same_token("deg/s", "deg/h")
    assert not same_token("2", "3")  # whole numbers (k2, gx100-01) are not rounded values


def test_text_must_match_word_for_word() -> None:
    assert same_text("k2: 3.2541818864e-08\n│ a │  1.5 │", "k2: 3.25418188644e-08\n│ a │ 1.5  │")
    assert not same_text("k2: 1.0\nk3: 2.0", "k2: 1.0 k3: 2.0")  # a line break is a token
    assert not same_text("k2: 1.0", "k3: 1.0")
    assert not same_text("k2: 1.0", "k2: 1.0 more")
