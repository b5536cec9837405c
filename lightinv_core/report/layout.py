"""The report's flow layout: blocks of known height poured onto A4 portrait pages.

A ``Block`` is a heading, a paragraph, a table or a drawing, with its height in
inches and a function that draws it into a matplotlib ``SubFigure`` of that height
and of the page's text width. ``flow`` fills each page top to bottom and starts a new
page only when the next block does not fit; a table that does not fit is split
between its rows ("(continued)"), so no page is left half empty by a page break
before a long table. A heading is never left alone at the bottom of a page. Every
page gets a footer (project, page n of N).

Tables are drawn as real text (selectable and searchable in the PDF) with cells
wrapped to their column, and their pass/fail cells coloured.
"""

from __future__ import annotations

import dataclasses
import textwrap
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure, SubFigure
from matplotlib.patches import Rectangle

from lightinv_core.report.tables import Table

A4_PORTRAIT = (8.27, 11.69)  # inches
MARGIN_X, MARGIN_TOP, MARGIN_BOTTOM = 0.6, 0.55, 0.75  # inches
TEXT_WIDTH = A4_PORTRAIT[0] - 2 * MARGIN_X
TEXT_HEIGHT = A4_PORTRAIT[1] - MARGIN_TOP - MARGIN_BOTTOM
GAP = 0.12  # inches between blocks
PASS_COLOUR, FAIL_COLOUR, HEAD_COLOUR, NOTE_COLOUR = "#d9f2d9", "#f8d0d0", "#e4e8f0", "0.3"
FONT = 8.0  # table text, points
LINE = 0.155  # inches per line of table text
CELL_CAP = 90  # characters of a cell before it wraps (narrowed when a table is too wide)


@dataclass
class Block:
    """One item of the flow: ``height`` inches, drawn by ``draw(subfigure)``.

    ``section`` names the part of the report it belongs to (the page names come from
    it); ``keep_with_next`` keeps a heading on the page of what follows; ``split``
    (tables) gives (what fits in ``height`` inches, the rest) or None when nothing fits.
    """

    height: float
    draw: Callable[[SubFigure], None]
    section: str = ""
    keep_with_next: bool = False
    split: Callable[[float], tuple[Block, Block] | None] | None = field(default=None, repr=False)
    min_height: float | None = None  # a drawing may shrink to this to fill a page

    def smallest(self) -> float:
        """The least height it can start a page's bottom with (a table: two rows)."""
        if self.split is not None:
            return min(self.height, 1.0)
        return self.min_height if self.min_height is not None else self.height


def heading(text: str, section: str, size: float = 13.0) -> Block:
    """A section heading, kept on the page of the block after it."""

    def draw(sf: SubFigure) -> None:
        sf.text(0.0, 0.5, text, fontsize=size, fontweight="bold", va="center")

    return Block(size / 72 * 1.6, draw, section, keep_with_next=True)


def paragraph(
    text: str | Sequence[str],
    section: str,
    size: float = 9.0,
    colour="0.1",
    keep_with_next: bool = False,
) -> Block:
    """Wrapped lines of text (one string is one paragraph; a list, one line each);
    ``keep_with_next``: an introduction, kept on the page of what follows."""
    chars = int(TEXT_WIDTH / (0.55 * size / 72))
    raw = [text] if isinstance(text, str) else list(text)
    lines = [w for line in raw for w in (textwrap.wrap(line, chars) or [""])]
    step = size / 72 * 1.45

    def draw(sf: SubFigure) -> None:
        h = max(len(lines), 1) * step
        for k, line in enumerate(lines):
            sf.text(0.0, 1 - (k + 0.5) * step / h, line, fontsize=size, va="center", color=colour)

    return Block(max(len(lines), 1) * step, draw, section, keep_with_next=keep_with_next)


def drawing(
    height: float, draw: Callable[[SubFigure], None], section: str, shrink: float = 0.55
) -> Block:
    """A plot or picture ``height`` inches tall, drawn into its subfigure by ``draw``;
    it may shrink to ``shrink`` x ``height`` to use the rest of a page."""
    return Block(height, draw, section, min_height=shrink * height)


def _widths(table: Table) -> tuple[list[int], list[list[list[str]]], float]:
    """Each column's width in characters, every cell wrapped to it and the font size:
    the largest of 8, 7.5 and 7 pt at which no data cell wraps (headers may), else 7 pt
    with the longest cells wrapped."""
    ncol = len(table.columns)
    cells = [list(table.columns)] + [list(r) for r in table.rows]
    words = [max(len(w) for c in cells for w in (c[j].split() or [""])) for j in range(ncol)]
    longest = [max([len(r[j]) for r in table.rows] or [1]) for j in range(ncol)]
    widths, size = words, FONT
    for size in (FONT, FONT - 0.5, FONT - 1.0):
        cap = CELL_CAP
        while True:
            widths = [max(words[j], min(cap, longest[j]), 1) for j in range(ncol)]
            fits = (sum(widths) + 2 * ncol) * char_width(size) <= TEXT_WIDTH
            if fits or cap <= 8 or size > FONT - 1.0:
                break
            cap -= 2
        if fits:
            break
    wrapped = [
        [textwrap.wrap(c[j], widths[j], break_long_words=True) or [""] for j in range(ncol)]
        for c in cells
    ]
    return widths, wrapped, size


def char_width(size: float) -> float:
    """Inches per character of table text at ``size`` points (DejaVu Sans, average)."""
    return 0.6 * size / 72


def table_block(table: Table, section: str, title: str | None = None) -> Block:
    """A table with its title (and note, after its last row); splits between rows."""
    return _table_part(table, section, range(len(table.rows)), title or table.title, True)


def _table_part(table: Table, section: str, rows: range, title: str, last: bool) -> Block:
    widths, wrapped, size = _widths(table)
    line = LINE * size / FONT
    head_lines = max(len(c) for c in wrapped[0])
    heights = [max(len(c) for c in wrapped[i + 1]) for i in rows]
    note = textwrap.wrap(table.note, int(TEXT_WIDTH / (0.55 * 8 / 72))) if last else []
    title_h, pad = 0.3, 0.05
    body = (head_lines + sum(heights) or 1) * line + pad * (len(rows) + 1)
    height = title_h + body + len(note) * 0.15 + (0.05 if note else 0.0)

    def draw(sf: SubFigure) -> None:
        H, W = height, TEXT_WIDTH
        sf.text(0.0, 1 - 0.15 / H, title, fontsize=11, fontweight="bold", va="center")
        y = H - title_h
        total = sum(widths) + 2 * len(widths)
        xs = [0.0]
        for w in widths:
            xs.append(xs[-1] + (w + 2) / total * W)
        lines_of = [head_lines, *heights]
        cells = [wrapped[0], *(wrapped[i + 1] for i in rows)]
        flags = ["head", *(table.flags[i] for i in rows)]
        for k, (cell_row, n) in enumerate(zip(cells, lines_of, strict=True)):
            h = n * line + pad
            colour = HEAD_COLOUR if k == 0 else "#f6f6f6" if k % 2 == 0 else "white"
            sf.add_artist(
                Rectangle((0, (y - h) / H), 1, h / H, transform=sf.transSubfigure, fc=colour)
            )
            if flags[k] in ("pass", "fail"):
                last_x = xs[-2] / W
                sf.add_artist(
                    Rectangle(
                        (last_x, (y - h) / H),
                        1 - last_x,
                        h / H,
                        transform=sf.transSubfigure,
                        fc=PASS_COLOUR if flags[k] == "pass" else FAIL_COLOUR,
                    )
                )
            for j, lines in enumerate(cell_row):
                for m, text in enumerate(lines):
                    sf.text(
                        (xs[j] + char_width(size)) / W,
                        (y - pad / 2 - (m + 0.5) * line) / H,
                        text,
                        fontsize=size,
                        va="center",
                        fontweight="bold" if k == 0 else "normal",
                    )
            y -= h
        sf.add_artist(
            Rectangle(
                (0, y / H),
                1,
                (H - title_h - y) / H,
                transform=sf.transSubfigure,
                fill=False,
                ec="0.6",
                lw=0.6,
            )
        )
        y -= 0.05
        for text in note:
            sf.text(0.0, (y - 0.075) / H, text, fontsize=8, va="center", color=NOTE_COLOUR)
            y -= 0.15

    def split(avail: float) -> tuple[Block, Block] | None:
        fixed = 0.3 + (head_lines * line + pad)
        n, used = 0, fixed
        for h in heights:
            if used + h * line + pad > avail:
                break
            used, n = used + h * line + pad, n + 1
        n = min(n, len(rows) - 2)  # no single row left on either page
        if n < 2:
            return None
        first = _table_part(table, section, rows[:n], title, False)
        more = title if title.endswith("(continued)") else f"{title} (continued)"
        return first, _table_part(table, section, rows[n:], more, last)

    return Block(height, draw, section, split=split)


@dataclass
class Page:
    """A composed page: its figure and the sections of the blocks on it."""

    figure: Figure
    sections: list[str]


def _need(queue: list[Block], i: int) -> float:
    """Height from block ``i`` down to the first block that needs not be kept with the
    one before it, counting that last block at its smallest."""
    total, k = 0.0, i
    while k < len(queue) - 1 and queue[k].keep_with_next:
        total += queue[k].height + GAP
        k += 1
    return total + (queue[k].smallest() if k > i else queue[k].height)


def compose(blocks: Sequence[Block]) -> list[list[Block]]:
    """The blocks of each page, in order: tables split where a page ends, a drawing
    shrunk (to its ``min_height`` at most) to use the end of a page, headings and
    introductions kept with what follows."""
    pages: list[list[Block]] = [[]]
    room = TEXT_HEIGHT
    queue = list(blocks)
    while queue:
        b = queue[0]
        gap = GAP if pages[-1] else 0.0
        if gap + _need(queue, 0) <= room:
            pages[-1].append(queue.pop(0))
            room -= gap + b.height
            continue
        fits = room - gap
        if not b.keep_with_next and b.min_height is not None and b.min_height <= fits:
            queue.pop(0)
            pages[-1].append(dataclasses.replace(b, height=fits))
            room = 0.0
            continue
        parts = b.split(fits) if b.split is not None and not b.keep_with_next else None
        if parts is not None:
            queue[0] = parts[1]
            pages[-1].append(parts[0])
        elif not pages[-1]:  # taller than a page and cannot split: squeezed onto one
            pages[-1].append(queue.pop(0))
        else:
            queue.insert(0, queue.pop(0))
        pages.append([])
        room = TEXT_HEIGHT
    return [p for p in pages if p]


def draw_page(items: Sequence[Block], number: int, total: int, footer: str = "") -> Page:
    """Page ``number`` of ``total``: its blocks drawn top to bottom, and the footer
    (``footer`` on the left, "page n of N" on the right)."""
    fig = Figure(figsize=A4_PORTRAIT, layout="constrained")
    FigureCanvasAgg(fig)
    fig.get_layout_engine().set(w_pad=0.02, h_pad=0.0, wspace=0.0, hspace=0.0)
    heights = [MARGIN_TOP]
    for k, b in enumerate(items):
        if k:
            heights.append(GAP)
        heights.append(min(b.height, TEXT_HEIGHT))
    heights.append(max(A4_PORTRAIT[1] - sum(heights), 1e-3))
    gs = fig.add_gridspec(
        len(heights),
        3,
        height_ratios=heights,
        width_ratios=[MARGIN_X, TEXT_WIDTH, MARGIN_X],
        hspace=0,
        wspace=0,
    )
    row = 1
    for k, b in enumerate(items):
        row += 1 if k else 0
        b.draw(fig.add_subfigure(gs[row, 1]))
        row += 1
    y = 0.4 / A4_PORTRAIT[1]
    x = MARGIN_X / A4_PORTRAIT[0]
    fig.text(x, y, footer, fontsize=8, color="0.35", va="center")
    fig.text(
        1 - x, y, f"page {number} of {total}", fontsize=8, color="0.35", va="center", ha="right"
    )
    return Page(fig, list(dict.fromkeys(b.section for b in items)))


def flow(blocks: Sequence[Block], footer: str = "") -> list[Page]:
    """Pour ``blocks`` onto A4 portrait pages, in order, and draw them (see
    ``compose`` and ``draw_page``). A block taller than a page gets a page of its own
    and is drawn squeezed to it."""
    laid = compose(blocks)
    return [draw_page(items, n, len(laid), footer) for n, items in enumerate(laid, 1)]


def page_names(pages: Sequence[Sequence[Block]]) -> list[str]:
    """A name for each page (its blocks): the first section on it (a section continued
    from the page before gets "-2", "-3", ...)."""
    names: list[str] = []
    seen: dict[str, int] = {}
    for p in pages:
        first = p[0].section if p else "page"
        seen[first] = seen.get(first, 0) + 1
        names.append(first if seen[first] == 1 else f"{first}-{seen[first]}")
    return names
