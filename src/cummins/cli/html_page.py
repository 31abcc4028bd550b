"""The HTML page of ``cummins report`` (:mod:`cummins.cli.html_report`): its parts and
its assembly.

:class:`Section` (a title and its HTML body), a matplotlib figure as an ``<img>`` with an
embedded PNG (``data:`` URI, :func:`figure_html`), tables (:func:`table_html`), notes,
a box for a model's failures (:func:`failures_html`), and the whole page with its inline
style sheet and table of contents (:func:`render_html`): no scripts, no request of its own.
"""

from __future__ import annotations

import base64
import html
import io
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import UTC, datetime

import numpy as np

_DPI = 80
_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;margin:0;color:#1d2433;
background:#fff}
header{background:#17324d;color:#fff;padding:1.2em 2em}
header h1{margin:0 0 .2em 0;font-size:1.5em}
header p{margin:0;opacity:.85}
main{padding:1em 2em;max-width:1200px}
h2{border-bottom:2px solid #17324d;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0 1.2em 0;font-size:.9em}
th,td{border:1px solid #c9d1dc;padding:.25em .6em;text-align:right}
th{background:#eef2f7}
td.text,th.text{text-align:left}
td.bad{background:#fbe3e3}
td.good{background:#e3f5e6}
td.warning{background:#fff3d6}
figure{margin:1em 0}
figure img{max-width:100%;border:1px solid #dde3ea}
figcaption{font-size:.85em;color:#4a5568}
p.note{color:#4a5568;font-size:.9em}
div.failures{background:#fbe3e3;border-left:6px solid #c53030;padding:.5em 1em;margin:.8em 0}
div.failures p{margin:.2em 0;font-weight:600}
div.failures ul{margin:.2em 0 .2em 1.2em;padding:0}
nav a{margin-right:1em}
"""


@dataclass(frozen=True)
class Section:
    """One part of a report: a title and its HTML body (tables, figures, notes)."""

    title: str
    body: str


def figure_html(fig, caption: str) -> str:
    """A matplotlib figure as an ``<img>`` with an embedded PNG, and its caption."""
    from cummins.plots import settle_layout

    buffer = io.BytesIO()
    settle_layout(fig, _DPI)
    fig.savefig(buffer, format="png", dpi=_DPI)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    text = html.escape(caption)
    return (
        f'<figure><img src="data:image/png;base64,{data}" alt="{text}">'
        f"<figcaption>{text}</figcaption></figure>"
    )


def table_html(
    header: Sequence[str],
    rows: Sequence[Sequence[object]],
    *,
    classes: Sequence[Sequence[str]] | None = None,
    caption: str = "",
) -> str:
    """An HTML table; text cells left-aligned, numbers right; optional cell classes."""
    out = ["<table>"]
    if caption:
        out.append(f"<caption>{html.escape(caption)}</caption>")
    if any(str(h) for h in header):
        out.append("<tr>" + "".join(f"<th>{html.escape(str(h))}</th>" for h in header) + "</tr>")
    for r, row in enumerate(rows):
        cells = []
        for c, value in enumerate(row):
            kind = [] if classes is None else [classes[r][c]] if classes[r][c] else []
            if isinstance(value, str):
                kind.append("text")
            attr = f' class="{" ".join(kind)}"' if kind else ""
            cells.append(f"<td{attr}>{html.escape(_cell(value))}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "".join(out)


def _cell(value: object) -> str:
    if isinstance(value, bool | np.bool_):
        return "yes" if value else "no"
    if isinstance(value, float | np.floating):
        return "–" if not np.isfinite(value) else f"{value:.4g}"
    return str(value)


def _note(text: str) -> str:
    return f'<p class="note">{html.escape(text)}</p>'


def failures_html(failures: Sequence[str], what: str) -> str:
    """A box that cannot be missed: ``what`` (the sentence that heads it) and one item
    per failure; empty without failures."""
    if not failures:
        return ""
    items = "".join(f"<li>{html.escape(str(f))}</li>" for f in failures)
    return f'<div class="failures"><p>{html.escape(what)}</p><ul>{items}</ul></div>'


def render_html(title: str, subtitle: str, sections: Sequence[Section]) -> str:
    """The whole page: inline CSS, a table of contents, the sections; no scripts."""
    from cummins._version import __version__

    nav = "".join(f'<a href="#s{k}">{html.escape(s.title)}</a>' for k, s in enumerate(sections))
    body = "".join(
        f'<section id="s{k}"><h2>{html.escape(s.title)}</h2>{s.body}</section>'
        for k, s in enumerate(sections)
    )
    stamp = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{html.escape(title)}</title><style>{_CSS}</style></head><body>"
        f"<header><h1>{html.escape(title)}</h1><p>{html.escape(subtitle)}</p>"
        f"<p>cummins {__version__}, {stamp}</p></header>"
        f"<main><nav>{nav}</nav>{body}</main></body></html>\n"
    )
