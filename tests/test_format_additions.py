"""The catalogue fields of datasheet sensors, responses, harmonic series and
accelerations (README, "Catalogue files"; docs/model.md sections 8-11): parsed values,
and every refusal located FILE:LINE:COL.

Every expected place is that of a token of the text (its last occurrence);
every broken file is refused by the JSON Schema too, except for the rules a
schema cannot say (a repeated order, breakpoint order).
"""

from __future__ import annotations

import jsonschema
import pytest

from gyrovib import models
from gyrovib.catalog.loader import CatalogError, _parse, parse_catalog
from gyrovib.models.schema import catalog_schema

FORMAT_EXAMPLE = """\
gyrovib: 1
units:
  rate: deg/s
  acceleration: g
sensors:
  - id: adis16460-coeffs
    range: 100
    coefficients: {A1: 2.0e-3, k3: -1.0e-6}
    g2_sensitivity: {G11: 4.0e-4, G22: 4.0e-4, G33: 4.0e-4, G12: 0.0, G13: 0.0, G23: 0.0}
    response:
      at: output
      table: [[10, 1.0], [500, 0.7]]
  - id: adis16460
    specs:
      range: 100
      nonlinearity: {value: 0.5, unit: "%FS", fit: least-squares, measure: max, of: range}
      asymmetry: {value: 500, unit: ppm}
      vre: 4.0e-4
profiles:
  - id: rotor
    rate: [0, 0, 20]
    harmonics:
      fundamental: 40
      orders:
        - {order: 1, amplitude: [0.1, 0.1, 0.5], phase: [0, 0, 0]}
        - {order: 2, amplitude: [0.0, 0.0, 0.3], phase: [0, 0, 90]}
    acceleration:
      harmonic:
        - {frequency: 120, amplitude: [0.5, 0.5, 2.0], phase: [0, 0, 0]}
      random:
        psd:
          x1: [[20, 0.04], [2000, 0.04]]
        coherence: [0, 0, 0]
      mount: [[20, 1.0], [200, 0.3]]
"""


def test_the_format_example_is_valid_and_exposed():
    model = parse_catalog(FORMAT_EXAMPLE, "ex.yaml").model
    assert model.acceleration_unit == "g"
    coeffs, specs = model.sensors
    # values as written in the example above
    assert coeffs.g2 == (4.0e-4, 4.0e-4, 4.0e-4, 0.0, 0.0, 0.0)
    assert coeffs.response_table == [(10.0, 1.0), (500.0, 0.7)]
    assert coeffs.response_at == "output"
    assert coeffs.specs is None
    assert specs.coefficients is None and specs.output_coefficients is None
    assert specs.specs.range == 100.0
    nl = specs.specs.nonlinearity
    assert (nl.value, nl.unit, nl.fit, nl.measure, nl.of) == (0.5, "%FS", "least-squares",
                                                              "max", "range")
    assert (specs.specs.asymmetry.value, specs.specs.asymmetry.unit) == (500.0, "ppm")
    assert specs.specs.vre == 4.0e-4
    assert specs.g2 == (0.0,) * 6  # a datasheet VRE is a bound, not the sensor's G
    (group,) = model.profiles[0].harmonics  # one group written: a list of one
    assert group.fundamental == 40.0
    assert [(o.order, o.amplitude, o.phase) for o in group.orders] == [
        (1, (0.1, 0.1, 0.5), (0.0, 0.0, 0.0)), (2, (0.0, 0.0, 0.3), (0.0, 0.0, 90.0))]
    acc = model.profiles[0].acceleration
    assert acc.harmonic[0].amplitude == (0.5, 0.5, 2.0)
    assert acc.random.psd.x1 == [(20.0, 0.04), (2000.0, 0.04)]
    assert acc.random.psd.x2 is None and acc.random.rms is None
    assert acc.random.coherence == (0.0, 0.0, 0.0)
    assert acc.mount == [(20.0, 1.0), (200.0, 0.3)]
    assert jsonschema.Draft7Validator(catalog_schema()).is_valid(
        _parse(FORMAT_EXAMPLE, "ex.yaml"))


def test_defaults_and_shorthands():
    model = parse_catalog("""\
gyrovib: 1
units: {acceleration: m/s2}
sensors:
  - id: a
    coefficients: {}
    vre: -2.5e-4 deg/s/g^2
    response: [[10, 1.0]]
  - id: b
    coefficients: {}
    response: {at: input, table: [[10, 1.0], [20, 0.5]]}
profiles:
  - id: p
    harmonics:
      - fundamental: 10
        orders: [{order: 3, amplitude: [0, 0, 1], phase: worst}]
      - fundamental: 25
        orders: [{order: 1.0, amplitude: [0, 0, 1]}]
    acceleration:
      random: {rms: [3, 3, 3]}
  - id: q
""").model
    assert model.acceleration_unit == "m/s^2"  # m/s2 is another spelling
    assert model.units.acceleration == "m/s2"  # kept as written
    a, b = model.sensors
    g = models.G2Quantity(value=-2.5e-4, unit="deg/s/g^2")
    assert a.g2 == (g, g, g, 0.0, 0.0, 0.0)  # signed, G11 = G22 = G33
    assert a.vre == g and a.g2_sensitivity is None
    assert (a.response_table, a.response_at) == ([(10.0, 1.0)], "output")  # a bare table: output
    assert (b.response_table, b.response_at) == ([(10.0, 1.0), (20.0, 0.5)], "input")
    assert b.g2 == (0.0,) * 6
    p, q = model.profiles
    first, second = p.harmonics
    assert first.orders[0].phase == "worst" and first.orders[0].worst_phase
    assert second.orders[0].order == 1 and type(second.orders[0].order) is int
    assert second.orders[0].phase == (0.0, 0.0, 0.0) and not second.orders[0].worst_phase
    assert p.acceleration.harmonic == [] and p.acceleration.random.rms == (3.0, 3.0, 3.0)
    assert p.acceleration.random.coherence == (0.0, 0.0, 0.0)  # independent axes
    assert p.acceleration.mount is None
    assert q.harmonics == [] and q.acceleration is None
    assert model.sensors[0].coefficients is not None  # the old forms keep their meaning


S = "gyrovib: 1\nsensors:\n  - id: s\n"
SPEC = S + "    specs:\n      range: 100\n"
P = "gyrovib: 1\nprofiles:\n  - id: p\n"
H = P + "    harmonics:\n      fundamental: 40\n      orders:\n"
A = P + "    acceleration:\n"

#: (text, token whose place is expected, words of the message)
CASES = [
    ("gyrovib: 1\nunits: {acceleration: mm/s2}\n", "mm/s2",
     ("unknown acceleration unit 'mm/s2'", "g, m/s^2, m/s2")),
    (S + "    coefficients: {}\n    vre: 1.0e-4\n    g2_sensitivity: {G11: 1}\n", "id: s",
     ("'vre'", "not both")),
    (S + "    coefficients: {}\n    g2_sensitivity: {G21: 1}\n", "G21", ("unknown key 'G21'",)),
    (S + "    coefficients: {}\n    g2_sensitivity: {G11: .inf}\n", ".inf", ("infinities",)),
    (S + "    coefficients: {}\n    vre: fast\n", "fast",
     ("cannot read 'fast' as a g² sensitivity", "0.0004 deg/s/g^2")),
    (S + "    coefficients: {}\n    response: {at: middle, table: [[1, 1]]}\n", "middle",
     ("unknown response position 'middle'", "output, input")),
    (S + "    coefficients: {}\n    response: {at: input}\n", "{at: input}",
     ("missing required key 'table'",)),
    (S + "    coefficients: {}\n    response: {at: input, table: [[20, 1], [10, 1]]}\n",
     "[10, 1]", ("must increase",)),
    (S + "    coefficients: {}\n    response: 5\n", "5", ("must be a list or mapping",)),
    (S + "    specs:\n      nonlinearity: {value: 1, unit: '%FS'}\n", "nonlinearity",
     ("missing required key 'range'",)),
    (S + "    specs:\n      range: 0\n      nonlinearity: {value: 1, unit: '%FS'}\n", "0",
     ("positive",)),
    (SPEC, "range", ("missing required key 'nonlinearity'",)),
    (SPEC + "      nonlinearity: {value: 0, unit: '%FS'}\n", "0,", ("positive",)),
    (SPEC + "      nonlinearity: {value: 1, unit: percent}\n", "percent",
     ("unknown nonlinearity unit 'percent'", "%FS, deg/s")),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS', fit: best}\n", "best",
     ("unknown fit 'best'", "least-squares, minimax, endpoint")),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS', fit: minimax, measure: rms}\n",
     "rms", ("RMS nonlinearity", "minimax")),
    (SPEC + "      nonlinearity: {value: 0.1, unit: deg/s, of: span}\n", "span",
     ("'of' applies to a nonlinearity in %FS only",)),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS', of: scale}\n", "scale",
     ("unknown base 'scale'", "range, span")),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS'}\n"
     "      asymmetry: {value: -1, unit: ppm}\n",
     "-1", ("must not be negative",)),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS'}\n"
     "      asymmetry: {value: 1, unit: ppb}\n",
     "ppb", ("unknown asymmetry unit 'ppb'", "ppm, %")),
    (SPEC + "      nonlinearity: {value: 1, unit: '%FS'}\n      vre: -1.0e-4\n", "-1.0e-4",
     ("must not be negative",)),
    (S + "    coefficients: {}\n    specs:\n      range: 1\n"
     "      nonlinearity: {value: 1, unit: '%FS'}\n", "id: s",
     ("conversion function once", "'specs'")),
    (P + "    harmonics:\n      fundamental: 0\n"
     "      orders: [{order: 1, amplitude: [0, 0, 1]}]\n",
     "0\n", ("fundamental", "positive")),
    (P + "    harmonics:\n      fundamental: -5\n"
     "      orders: [{order: 1, amplitude: [0, 0, 1]}]\n",
     "-5", ("positive",)),
    (H + "        - {order: 1.5, amplitude: [0, 0, 1]}\n", "1.5", ("must be an integer",)),
    (H + "        - {order: 0, amplitude: [0, 0, 1]}\n", "0, amplitude",
     ("must not be less than 1",)),
    (H + "        - {order: two, amplitude: [0, 0, 1]}\n", "two", ("must be an integer",)),
    (H + "        - {order: 2, amplitude: [0, 0, 1]}\n"
     "        - {order: 1, amplitude: [0, 0, 1]}\n"
     "        - {order: 2, amplitude: [1, 0, 1]}\n", "2, amplitude: [1",
     ("order 2 is given twice", "first as item 1")),
    (H + "        - {order: 1, amplitude: [0, 0, 1], phase: [worst, 0, 0]}\n", "worst",
     ("'worst' stands for the whole list",)),
    (H + "        - {order: 1, amplitude: [0, 0, 1], phase: best}\n", "best",
     ("unknown phase 'best'", "worst")),
    (H + "        - {order: 1, amplitude: [0, 0, 1], phase: [0, 90]}\n", "[0, 90]",
     ("too few values",)),
    (H + "".join(f"        - {{order: {n}, amplitude: [0, 0, 1]}}\n" for n in range(1, 66)),
     "- {order: 1,", ("too many values (65; expected at most 64)",)),
    (H + "      - x\n", "x\n", ("mapping",)),
    (P + "    harmonics:\n      fundamental: 40\n      orders: []\n", "[]", ("too few values",)),
    (P + "    harmonics:\n      - fundamental: 40\n"
     "        orders: [{order: 1, amplitude: [0, 0, 1]}]\n"
     "      - fundamental: 50\n        orders: [{order: 1, amplitude: [0, 0, -1]}]\n", "-1]",
     ("harmonics[1].orders[0].amplitude[2]", "negative")),
    (A + "      harmonic: [{frequency: 10, amplitude: [0, -2, 0]}]\n", "-2",
     ("negative",)),
    (A + "      harmonic: [{frequency: 0, amplitude: [0, 2, 0]}]\n", "0, amplitude",
     ("positive",)),
    (A + "      random: {rms: [1, 1, 1], psd: {x1: [[1, 1], [2, 1]]}}\n", "{rms",
     ("exactly one",)),
    (A + "      random: {rms: [1, 1, 1], coherence: [0, 0, 2]}\n", "2]", ("[-1, 1]",)),
    (A + "      random: {rms: [1, 1, 1], coherence: [0, 0]}\n", "[0, 0]", ("too few",)),
    (A + "      random: {psd: {x2: [[20, 0.04]]}}\n", "[[20", ("two different frequencies",)),
    (A + "      random: {psd: {}}\n", "{}", ("at least one axis",)),
    (A + "      mount: [[200, 1], [20, 1]]\n", "[20, 1]", ("must increase",)),
    (A + "      random: {rms: [1, 1, 1]}\n      mass: 3\n", "mass",
     ("unknown key 'mass'", "harmonic, random, mount")),
]

#: Rules no JSON Schema can say (a one-point PSD it can: minItems).
INEXPRESSIBLE = ("given twice", "must increase")


def _place(text: str, token: str) -> tuple[int, int]:
    offset = text.rindex(token)
    return text.count("\n", 0, offset) + 1, offset - (text.rfind("\n", 0, offset) + 1) + 1


@pytest.mark.parametrize(("text", "token", "words"), CASES,
                         ids=[f"{i}-{c[2][0][:30]}" for i, c in enumerate(CASES)])
def test_refusals_are_located(text: str, token: str, words: tuple[str, ...]) -> None:
    line, column = _place(text, token)
    with pytest.raises(CatalogError) as info:
        parse_catalog(text, "cat.yaml")
    first = str(info.value).splitlines()[0]
    assert first.startswith(f"cat.yaml:{line}:{column}: "), first
    for word in words:
        assert word in first, first
    assert len(info.value.problems) == 1, str(info.value)
    schema_ok = jsonschema.Draft7Validator(catalog_schema()).is_valid(_parse(text, "cat.yaml"))
    assert schema_ok == any(w in first for w in INEXPRESSIBLE), first


def test_a_datasheet_sensor_has_no_coefficients_to_hand_out():
    model = parse_catalog(FORMAT_EXAMPLE, "ex.yaml").model
    assert model.sensors[0].rate_coefficients.k3 == -1.0e-6
    with pytest.raises(CatalogError, match="'adis16460' is given by its datasheet"):
        model.sensors[1].rate_coefficients  # noqa: B018
