"""The gallery's image scraper for cummins' figures.

cummins draws on :class:`matplotlib.figure.Figure` objects, not pyplot's state (the
figures work alike in a script, a notebook and on a server), so sphinx-gallery's own
matplotlib scraper does not see them. This one takes every ``Figure`` an example's code
block left in its variables (a name bound to a figure, or a list or dict of figures) that
it has not shown yet, and writes it as the block's images.
"""

from __future__ import annotations

from matplotlib.figure import Figure
from sphinx_gallery.scrapers import figure_rst

#: The figures already shown, per example file (a variable may keep its figure).
_SHOWN: dict[str, set[int]] = {}


def _figures(value) -> list[Figure]:
    if isinstance(value, Figure):
        return [value]
    if isinstance(value, list | tuple):
        return [v for v in value if isinstance(v, Figure)]
    if isinstance(value, dict):
        return [v for v in value.values() if isinstance(v, Figure)]
    return []


def figure_scraper(block, block_vars, gallery_conf, **kwargs) -> str:
    """The rST of the new figures of a code block (sphinx-gallery's scraper interface)."""
    shown = _SHOWN.setdefault(str(block_vars["src_file"]), set())
    found: list[Figure] = []
    for name, value in block_vars["example_globals"].items():
        if name.startswith("_"):
            continue
        for fig in _figures(value):
            if id(fig) not in shown and all(fig is not f for f in found):
                found.append(fig)
    from cummins.plots import settle_layout

    paths = []
    for fig, path in zip(found, block_vars["image_path_iterator"], strict=False):
        settle_layout(fig, 90)  # no label cut at the edge (cummins.plots.save_figure)
        fig.savefig(path, dpi=90)
        shown.add(id(fig))
        paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])
