"""The package cites the literature, and every work it cites is listed in full.

A citation is *Author (year)*, *Author & Author (year)*, *Author et al. (year)* or the same
inside parentheses (*Author, year* / *Author year*); every one found in the package, the
README and the docs must have an entry in ``docs/references.md``. No internal file
number ("seed 004") may remain: users have the papers, not our file names.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
REFERENCES = (ROOT / "docs" / "references.md").read_text(encoding="utf-8")

#: Any run of white space, a line break and the next line's indentation included: a
#: citation wrapped in a docstring is still one citation.
SPACE = r"\s+"
NAME = rf"(?:[Dd]e{SPACE}|[Vv]an{SPACE})?[A-Z][a-zA-Zøéü-]+"
AUTHORS = rf"{NAME}(?:(?:,{SPACE}{NAME})*,?{SPACE}(?:&|and){SPACE}{NAME}|{SPACE}et{SPACE}al\.)?"
#: "Author (2004)", "Author et al. (2004)", "Author & Author (2004)"
CITED = re.compile(rf"\b({AUTHORS}){SPACE}\(((?:19|20)\d\d)[a-z]?\)")
#: "(Author 2004", "(Author, 2004" — a citation inside parentheses
PARENTHESISED = re.compile(rf"\(({AUTHORS}),?{SPACE}((?:19|20)\d\d)[a-z]?\b")

#: Words that look like a name before a year but are not a citation.
NOT_AUTHORS = {"Copyright", "Version", "ISO", "Release", "Python", "January", "December"}


def _sources() -> list[Path]:
    files = sorted((ROOT / "src" / "cummins").rglob("*.py"))
    files += [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    # the site's pages and the gallery's examples (docs/_build and generated pages aside)
    files += sorted(
        f
        for f in (ROOT / "docs").glob("*/*.md")
        if f.parts[-2] in ("guide", "theory") and not f.name.endswith(".inc.md")
    )
    files += sorted((ROOT / "examples").glob("*.py"))
    return [f for f in files if f.name != "references.md"]


def _citations() -> set[tuple[str, str, str]]:
    found = set()
    for path in _sources():
        text = path.read_text(encoding="utf-8")
        for pattern in (CITED, PARENTHESISED):
            for match in pattern.finditer(text):
                authors, year = " ".join(match.group(1).split()), match.group(2)
                if authors.split()[0] in NOT_AUTHORS:
                    continue
                found.add((authors, year, path.name))
    return found


def _key(authors: str) -> str:
    """The first author's surname, as the entry starts with it ("de Haan" for "De Haan")."""
    first = re.split(r",| & | and | et al\.", authors)[0].strip()
    return first


def test_every_cited_work_has_an_entry():
    missing = sorted(
        {
            f"{authors} ({year}) in {where}"
            for authors, year, where in _citations()
            if not re.search(
                rf"\*\*{re.escape(_key(authors))}[^*]*\({year}\)", REFERENCES, re.IGNORECASE
            )
        }
    )
    assert not missing, "\n".join(missing)


def test_citations_are_found():
    """The scan is not vacuous: the works the package is built on are cited."""
    cited = {(_key(a), y) for a, y, _ in _citations()}
    for work in (("Unneland", "2007"), ("Hjulstad", "2004"), ("Smogeli", "2004")):
        assert work in cited


def test_no_internal_file_numbers():
    """No "seed 004", "seed 001 Table 5.1" or "digest §1.3" in what users read."""
    pattern = re.compile(r"\bseeds? 00\d|\bdigest §|seeds/digests", re.IGNORECASE)
    hits = []
    for path in _sources():
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if pattern.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:80]}")
    assert not hits, "\n".join(hits)
