"""Every model citation resolves: the code, README and docs cite the model as
``docs/model.md section N``, and docs/model.md has that section (the file the
output names must exist in the repository), and nothing cites a document that does not
ship with it."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT / "docs" / "model.md"
#: Files of the catalogue format that another change replaces (pydantic models);
#: their citations move with them.
ELSEWHERE: set[str] = set()
CITATION = re.compile(r"model\.md,?\s+(?:sections?\s*|§\s*)?"
                      r"((?:\d+(?:\.\d+)?(?:\s*(?:,|and|–|-)\s*)?)+)")


def sources() -> list[Path]:
    found = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    for pattern in ("*.py", "*.yaml"):
        found += sorted((ROOT / "src").rglob(pattern))
    return [p for p in found if str(p.relative_to(ROOT)) not in ELSEWHERE]


def sections() -> set[str]:
    heads = re.findall(r"^#{2,3} (\d+(?:\.\d+)?)\.? ", MODEL.read_text(encoding="utf-8"),
                       flags=re.M)
    return set(heads)


def numbers(text: str) -> list[str]:
    """'8 and 11' -> ['8', '11']; '12–14' -> ['12', '13', '14']."""
    out: list[str] = []
    for a, b in re.findall(r"(\d+(?:\.\d+)?)(?:\s*[–-]\s*(\d+))?", text):
        out += [a] if not b else [str(k) for k in range(int(a), int(b) + 1)]
    return out


def test_the_model_has_the_sections_the_output_cites() -> None:
    # 1–14 as the model is numbered (the code cites 8–11 most), 4.1 within 4
    assert {str(k) for k in range(1, 15)} | {"4.1"} <= sections()


def test_no_citation_names_a_file_that_is_not_there() -> None:
    stale = [f"{p.relative_to(ROOT)}:{n}" for p in sources()
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if "MODEL.md" in line]
    assert not stale, f"cite docs/model.md, which ships: {stale[:5]}"


def test_every_section_cited_exists() -> None:
    have = sections()
    cited = 0
    for path in sources():
        text = path.read_text(encoding="utf-8")
        for match in CITATION.finditer(text):
            for number in numbers(match.group(1)):
                cited += 1
                assert number in have, (f"{path.relative_to(ROOT)} cites docs/model.md "
                                        f"section {number}, which it does not have")
    assert cited > 50  # the check ran over the citations (the code has ~100)


def test_the_model_cites_its_own_sections() -> None:
    text = MODEL.read_text(encoding="utf-8")
    have = sections()
    for match in re.finditer(r"\bsections? ((?:\d+(?:\.\d+)?(?:\s*(?:,|and|–|-)\s*)?)+)", text):
        for number in numbers(match.group(1)):
            assert number in have, f"docs/model.md cites its section {number}"


def test_nothing_cites_a_document_outside_the_repository() -> None:
    # The format's and the model's references ship as README.md and docs/; a reader of
    # the code, the tests or the benchmarks can open every document they name.
    here = Path(__file__).resolve()
    files = [*sources(), *sorted((ROOT / "tests").rglob("*.py")),
             *sorted((ROOT / "benchmarks").rglob("*.py"))]
    stale = [f"{p.relative_to(ROOT)}:{n}" for p in files if p != here
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if re.search(r"\b(INTERFACE|MODEL)\.md", line)]
    assert not stale, f"cite README.md or docs/ instead: {stale[:5]}"
