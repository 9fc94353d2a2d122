"""Random mutations of valid catalogues: the loader answers 0 or 2, never a traceback."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gyrovib.catalog import loader
from tests.conftest import VALID, invoke

SEEDS = [VALID] + [p.read_text(encoding="utf-8") for p in loader.bundled_paths()]

SCALARS = [
    "", "~", "null", "0", "-0", "1", "-1", "1e400", "-1e400", ".nan", ".inf", "-.inf", "1e-400",
    "true", "no", "yes", "abc", "'x y'", '"a/b"', "[]", "{}", "[1, 2]", "[[1, 2]]", "*nope",
    "&a", "!!python/name:os.system", "!foo", "<<", "- ", ": ", "[", "{", "'", '"', "#", "|",
    ">", "%YAML 1.1", "---", "...", "\t", "1" * 400, "0x10", "1_000", "12:30", "2001-12-14",
]


@st.composite
def mutated(draw: st.DrawFn) -> bytes:
    text = draw(st.sampled_from(SEEDS))
    lines = text.splitlines(keepends=True)
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["flip", "delete", "duplicate", "scalar", "insert", "swap"]))
        if not lines:
            lines = ["\n"]
        i = draw(st.integers(0, len(lines) - 1))
        if kind == "delete":
            del lines[i]
        elif kind == "duplicate":
            lines.insert(i, lines[i])
        elif kind == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif kind == "scalar":
            line = lines[i]
            cut = line.rfind(": ")
            cut = cut + 2 if cut >= 0 else draw(st.integers(0, len(line)))
            lines[i] = line[:cut] + draw(st.sampled_from(SCALARS)) + "\n"
        elif kind == "insert":
            lines.insert(i, draw(st.sampled_from(SCALARS)) + "\n")
        else:  # flip bytes in the line
            raw = bytearray(lines[i].encode("utf-8"))
            if raw:
                for _ in range(draw(st.integers(1, 3))):
                    k = draw(st.integers(0, len(raw) - 1))
                    raw[k] = draw(st.integers(0, 255))
            return b"".join(x.encode("utf-8") for x in lines[:i]) + bytes(raw) + \
                b"".join(x.encode("utf-8") for x in lines[i + 1:])
    return "".join(lines).encode("utf-8")


@pytest.fixture(scope="module")
def fuzz_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("fuzz")


@settings(max_examples=200, deadline=None, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(data=mutated(), command=st.sampled_from(["validate", "analyze"]))
def test_mutated_catalogue_never_crashes(fuzz_dir: Path, data: bytes, command: str) -> None:
    path = fuzz_dir / "mutant.yaml"
    path.write_bytes(data)
    result = invoke(command, path, *(["--format", "json"] if command == "analyze" else []))
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        repr(result.exception), data[:2000])
    assert result.exit_code in (0, 2), (result.exit_code, result.stderr, data[:2000])
    assert "Traceback" not in result.stderr
    if result.exit_code == 2:
        lines = result.stderr.strip().splitlines()
        assert lines
        for line in lines:
            assert line.startswith((f"{path}", "gyrovib: error: ")), line
    elif command == "analyze":
        assert "NaN" not in result.stdout and "Infinity" not in result.stdout
