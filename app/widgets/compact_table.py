"""The tables of the luminaires panel: a read-only table that asks for three rows'
height, and the arrays table's product title."""

from __future__ import annotations

import textwrap
from pathlib import Path

from PySide6 import QtCore, QtWidgets

from lightinv_core.light.arrays import Product
from lightinv_core.luminaires.formats import is_photometry_reference


def product_title(product: str, p: Product) -> tuple[str, str]:
    """(what the arrays table shows, its tooltip) of an array's ``product`` resolved as
    ``p``: a catalogue product's name (catalogue number); a photometric file's maker and
    catalogue number (its file name without one). An IES file's [LUMINAIRE] is a
    description ("FROSTED TRANSLUCENT PLASTIC DIFFUSER, ...") and goes in the tooltip."""
    ph = p.photometry
    number = " ".join(ph.catalogue_number.split())
    path = Path(product)
    if is_photometry_reference(product):
        maker = " ".join(ph.manufacturer.split())
        title = " ".join(t for t in (maker, number) if t) or path.stem
        about = (textwrap.fill(ph.name, 60), f"file {path.name}")  # a tooltip does not wrap
    else:
        title = f"{p.name} ({number})" if number else p.name
        about = (ph.name if ph.name != p.name else "",)
    rating = f"{p.lumens:,.0f} lm, {p.watts:g} W"
    return title, "\n".join(t for t in (*about, rating) if t)


class CompactTable(QtWidgets.QTableWidget):
    """A table that asks for three rows' height: a word-wrapped warning makes the
    panel's layout give a box its preferred height, and a table's usual one squeezed
    the catalogue box below its minimum, cutting the polar curve off (1366 x 768)."""

    ROWS = 3

    def resizeEvent(self, event) -> None:
        """Keep the chosen row in view when the panel's layout shrinks the table (it
        shows one row at 1366 x 768 once the arrays and work planes fill in)."""
        super().resizeEvent(event)
        if self.currentItem() is not None:
            self.scrollToItem(self.currentItem())

    def sizeHint(self) -> QtCore.QSize:
        rows = self.ROWS * self.verticalHeader().defaultSectionSize()
        bar = self.horizontalScrollBar().sizeHint().height()
        height = self.horizontalHeader().sizeHint().height() + rows + bar + 2 * self.frameWidth()
        return QtCore.QSize(super().sizeHint().width(), height)


def compact_table(columns: tuple[str, ...]) -> QtWidgets.QTableWidget:
    """A read-only table selected by rows."""
    table = CompactTable(0, len(columns))
    table.setHorizontalHeaderLabels(columns)
    table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
    table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
    table.verticalHeader().hide()
    return table
