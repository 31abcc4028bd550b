"""Detection of AQWA output by its content: the ``.LIS`` listing and the ``.AH1`` database.

A listing carries the AQWA banner (``DECK`` cards or letter-spaced ``* * * *`` titles);
a database starts with ``*`` header lines, then ``nbodies ndirections nfrequencies``
and keyword sections (GENERAL, COG, ADDEDMASS, HYDSTIFFNESS …); a QTF file's first line
is ``AQTF-2.0``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from cummins.io._text import parse_numbers

# --------------------------------------------------------------------------- detection


def _head(path: Path, size: int = 8192) -> str:
    with open(path, "rb") as f:
        return f.read(size).decode("utf-8-sig", errors="replace")


def _is_lis(head: str) -> bool:
    upper = head.upper()
    return "AQWA" in upper and ("DECK" in upper or "* * * *" in upper)


def _is_ah1(head: str) -> bool:
    lines = [line for line in head.splitlines() if line.strip()]
    body = [line for line in lines if not line.lstrip().startswith("*")]
    if not body:
        return False
    first = parse_numbers(body[0])
    if first is None or first.size < 3 or not np.all(first[:3] == np.round(first[:3])):
        return False
    keywords = {line.strip() for line in body}
    return bool(keywords & {"GENERAL", "COG", "ADDEDMASS", "HYDSTIFFNESS"})


def _is_qtf(head: str) -> bool:
    """AQWA's ``.QTF``: its first line is ``AQTF-<version>``."""
    return head.lstrip().startswith("AQTF-")


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` an AQWA ``.LIS`` listing, ``.AH1`` database or
    ``.QTF`` (recognised to say which file of the run to read)?"""
    path = Path(path)
    if not path.is_file():
        return False
    head = _head(path, 65536)
    return _is_lis(head[:8192]) or _is_ah1(head) or _is_qtf(head)


def sniff_dir(path: Path) -> list[Path]:
    """The AQWA runs in a folder: each ``.LIS``, and each ``.AH1`` without a ``.LIS``."""
    path = Path(path)
    files = sorted(p for p in path.iterdir() if p.is_file())
    lis = [p for p in files if p.suffix.lower() == ".lis" and _is_lis(_head(p))]
    stems = {p.stem.lower() for p in lis}
    ah1 = [
        p
        for p in files
        if p.suffix.lower() == ".ah1" and p.stem.lower() not in stems and _is_ah1(_head(p, 65536))
    ]
    return lis + ah1
