"""Catalogue loading: numbers as people write them, located errors, merging."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.catalog.loader import CatalogError, load_catalog, parse_catalog


def test_exponent_without_dot_is_a_number():
    # plain YAML 1.1 reads 1e-5 as a string; gyrovib reads it as 1e-5
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: 1e-5, k3: 2E+3}\n")
    c = src.model.sensors[0].coefficients
    assert (c.k2, c.k3) == (1e-5, 2000.0)


def test_yes_no_and_dates_stay_strings():
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n    name: no\n    notes: 2024-01-01\n"
                        "    coefficients: {}\n")
    assert src.model.sensors[0].name == "no"
    assert src.model.sensors[0].notes == "2024-01-01"


ERRORS = [
        ("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k_2: 1}\n", "k_2",
         "did you mean 'k2'"),
        ("gyrovib: 1\nunits: {rate: deg/min}\n", "deg/min", "deg/s"),
        ("gyrovib: 1\nx: 1\nx: 2\n", "x: 2", "duplicate key"),
        ("gyrovib: 2\n", "2", "unsupported format version"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    harmonic: [{frequency: 0, amplitude: [1, 1, 1]}]\n",
         "0,", "greater than 0"),
        ("gyrovib: 1\nsensors:\n  - id: s\n    output_coefficients: {K1: 0}\n", "0}", "K1"),
        ("gyrovib: 1\nsensors:\n  - id: a b\n    coefficients: {}\n", "a b", "no spaces"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    mount: [[20, 1], [10, 1]]\n", "[10",
         "must increase"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    random: {rms: [1, 1, 1], coherence: [2, 0]}\n",
         "2, 0]", "lies in [-1, 1]"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    rate: [0, 0, .nan]\n", ".nan", "finite"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    rate: [0, 0, 1e400]\n", "1e400", "finite"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    rate: [0, 0]\n", "[0, 0]", "too few"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    rate: [0, 0, fast]\n", "fast", "number"),
]
ERROR_TEXTS = [e[0] for e in ERRORS]


@pytest.mark.parametrize(("text", "token", "fragment"), ERRORS)
def test_errors_name_file_line_and_column(text, token, fragment):
    # the expected place is that of ``token`` (its last occurrence) in the text
    offset = text.rindex(token)
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    with pytest.raises(CatalogError) as info:
        parse_catalog(text, "cat.yaml")
    message = str(info.value)
    assert message.startswith(f"cat.yaml:{line}:{column}:"), message
    assert fragment in message


def test_missing_version_points_at_the_top():
    with pytest.raises(CatalogError, match=r"^cat.yaml:1:1: .*gyrovib: 1"):
        parse_catalog("sensors: []\n", "cat.yaml")


def test_duplicate_ids_across_files(tmp_path):
    a = tmp_path / "a.yaml"
    b = tmp_path / "b.yaml"
    a.write_text("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {}\n")
    b.write_text("gyrovib: 1\nsensors:\n  - id: t\n    coefficients: {}\n"
                 "  - id: s\n    coefficients: {}\n")
    with pytest.raises(CatalogError) as info:
        load_catalog([a, b])
    assert str(info.value) == f"{b}:5:9: duplicate sensor id 's' (first at {a}:3)"


def test_merged_catalogue_keeps_order(tmp_path):
    a = tmp_path / "a.yaml"
    b = tmp_path / "b.yaml"
    a.write_text("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {}\n")
    b.write_text("gyrovib: 1\nprofiles:\n  - id: p\n")
    cat = load_catalog([a, b])
    assert [e.sensor.id for e in cat.sensors] == ["s"]
    assert [e.profile.id for e in cat.profiles] == ["p"]


def test_object_tags_are_refused_and_run_nothing(tmp_path):
    marker = tmp_path / "pwned"
    text = f"gyrovib: 1\nx: !!python/object/apply:os.system ['touch {marker}']\n"
    with pytest.raises(CatalogError, match="not allowed"):
        parse_catalog(text, "evil.yaml")
    assert not marker.exists()


def test_a_file_is_composed_once_for_any_number_of_locations(monkeypatch):
    # `select --format github` locates every sensor: one composition, then direct steps
    from gyrovib.catalog import locate

    calls = []
    real = locate._compose
    monkeypatch.setattr(locate, "_compose", lambda text: calls.append(1) or real(text))
    text = "gyrovib: 1\nsensors:\n" + "".join(
        f"  - id: s{i}\n    coefficients: {{}}\n" for i in range(500))
    src = parse_catalog(text, "cat.yaml")
    assert calls == []  # a valid file is never composed just to be loaded
    places = [src.locate(("sensors", i, "id")) for i in range(500)]
    assert places == [(3 + 2 * i, 9) for i in range(500)]  # "  - id: sI" on line 3 + 2i
    assert calls == [1]


@settings(deadline=None, max_examples=300)
@given(st.lists(st.sampled_from(["", ".", "..", "a", "b.yaml", " ", "a b"]), max_size=5)
       .map("/".join))
def test_the_file_opened_is_the_one_pathlib_would_open(name: str) -> None:
    # read_catalog opens _native(path) without importing pathlib (a first-run cost);
    # the reference is pathlib itself: Path(name).open() opens str(Path(name))
    from pathlib import Path

    from gyrovib.catalog.loader import _native

    assert _native(name) == str(Path(name))
    assert _native(Path(name)) == str(Path(name))


def test_bundled_files_are_the_bundled_paths() -> None:
    from gyrovib.catalog.loader import bundled_files, bundled_paths

    assert bundled_files() == [str(p) for p in bundled_paths()]
    assert len(bundled_files()) == 3  # missions, profiles, sensors


def test_a_one_of_rule_is_reported_beside_other_problems_of_its_entry():
    # every problem in one run: each entry below also has a bad value, and the
    # "give exactly one of" rules must be reported with it, not after it is mended
    text = """gyrovib: 1
sensors:
  - id: s1
    coefficients: {k2: 1.0e-6}
    vre: 4.0e-4
    g2_sensitivity: {G11: 1.0e-4}
    response: {at: middle, table: [[10, 1.0]]}
  - id: s2
    coefficients: {k2: 1.0e-6}
    specs: {range: 100, nonlinearity: {value: 0.1, unit: "%FS"}}
    range: -3
profiles:
  - id: p
    acceleration:
      random:
        psd: {x1: [[20, 0.04], [2000, 0.04]]}
        rms: [1, 1, 1]
        coherence: [2, 0, 0]
"""
    with pytest.raises(CatalogError) as err:
        parse_catalog(text, "f.yaml")
    lines = str(err.value).splitlines()
    expected = [
        ("f.yaml:3:5:", "'g2_sensitivity' or its shorthand 'vre'"),
        ("f.yaml:7:20:", "unknown response position 'middle'"),
        ("f.yaml:8:5:", "give the conversion function once"),
        ("f.yaml:11:12:", "range: must be positive"),
        ("f.yaml:16:9:", "as 'psd' or as 'rms', exactly one"),
        ("f.yaml:18:21:", "coherence[0]: must not be greater than 1"),
    ]
    assert len(lines) == len(expected)
    for line, (where, what) in zip(lines, expected, strict=True):
        assert line.startswith(where) and what in line, line
