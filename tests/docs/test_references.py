"""The project's own documents hold what its code and documents refer to (issue 27): every "docs/design.md §N"
names a section of docs/design.md, every "docs/algorithms.md §N" one of docs/algorithms.md, every ADR cited
by number exists, and no citation names a document the repository does not contain."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCES = [
    p
    for folder in ("model", "app", "views", "tests", "benchmarks", "docs", "resources")
    for p in (ROOT / folder).rglob("*")
    if p.suffix in (".py", ".md", ".rst")
    and "_build" not in p.parts
    and p.name not in ("design.md", "algorithms.md")
] + [ROOT / "README.md"]


def _sections(doc: Path) -> set[str]:
    """The section numbers of a document: "## 3. …" gives 3, "### 2.4 …" gives 2.4 (and 2)."""
    found = set()
    for line in doc.read_text(encoding="utf-8").splitlines():
        m = re.match(r"#+\s+(\d+(?:\.\d+)*)[.\s]", line)
        if m:
            found.add(m.group(1))
    return found


def _cited(pattern: str) -> list[tuple[Path, str]]:
    out = []
    for p in SOURCES:
        for m in re.finditer(pattern, p.read_text(encoding="utf-8")):
            out.append((p.relative_to(ROOT), m.group(1)))
    return out


def test_every_cited_section_of_the_design_and_the_brief_exists() -> None:
    for doc, name in (
        (ROOT / "docs" / "design.md", "design"),
        (ROOT / "docs" / "algorithms.md", "algorithms"),
    ):
        sections = _sections(doc)
        cited = _cited(rf"docs/{name}\.md §\s*(\d+(?:\.\d+)?)")
        assert cited, f"nothing cites docs/{name}.md"
        # "§3.6" of the design is item 6 of section 3: its section is 3.
        missing = [(p, s) for p, s in cited if s not in sections and s.split(".")[0] not in sections]
        assert not missing, f"sections of docs/{name}.md that do not exist: {missing[:10]}"


def test_no_citation_names_a_document_the_repository_lacks() -> None:
    bare = _cited(r"(?<![\w/.])((?:DESIGN|ALGORITHMS)(?:\.md)? §)")
    assert not bare, f"cite docs/design.md or docs/algorithms.md instead: {bare[:10]}"
    adrs = {int(p.name[:4]) for p in (ROOT / "docs" / "adr").glob("[0-9][0-9][0-9][0-9]-*.md")}
    cited = {(p, int(n)) for p, n in _cited(r"ADR (\d{4})\b")}
    missing = sorted((str(p), n) for p, n in cited if n not in adrs)
    assert not missing, f"ADRs cited that do not exist: {missing[:10]}"
