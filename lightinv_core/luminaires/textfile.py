"""Photometric text files: size limits, decoding, numbers with line numbers, formatting.

Both formats are small text files (a few kB to a few hundred kB). Anything over
``MAX_FILE_BYTES`` is refused before it is read, counts over ``MAX_ANGLES`` before
anything is allocated, so a corrupt header cannot ask for gigabytes.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from lightinv_core.luminaires.photometry import fail, quote
from lightinv_core.textcodec import decode_text

MAX_FILE_BYTES = 20_000_000
"""Bytes (20 MB); real IES and LDT files are under 1 MB."""

MAX_ANGLES = 10_000
"""Most angles of one kind in a table (0.036 degree steps over 360)."""

MAX_VALUES = 1_000_000
"""Most intensities in one table (8 MB as float64)."""

MAX_CANDELA = 1e12
"""cd; the brightest searchlights reach about 1e9. Larger values are corrupt files."""

MAX_LUMENS = 1e10
"""lm; the cap the project puts on any source's flux."""

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_LINE_BREAK = re.compile(r"\r\n|\r|\n")


def read_bytes(path: str | os.PathLike) -> bytes:
    """The bytes of a photometric file, or a PhotometryError saying why not."""
    source = str(path)
    p = Path(path)
    try:
        size = p.stat().st_size
    except FileNotFoundError:
        raise fail(source, None, "no such file", "check the path") from None
    except OSError as exc:
        raise fail(source, None, f"cannot read: {exc.strerror}", "check the path") from None
    if p.is_dir():
        raise fail(source, None, "is a folder", "give a photometric file (.ies or .ldt)")
    if size > MAX_FILE_BYTES:
        raise fail(
            source,
            None,
            f"{size / 1e6:.1f} MB is too large for a photometric file "
            f"(limit {MAX_FILE_BYTES / 1e6:.0f} MB)",
            "check that this is an IES or EULUMDAT file",
        )
    try:
        with open(p, "rb") as fh:
            data = fh.read(MAX_FILE_BYTES + 1)  # a file that grew since stat() stops here
    except OSError as exc:
        raise fail(source, None, f"cannot read: {exc.strerror}", "check the path") from None
    if len(data) > MAX_FILE_BYTES:
        raise fail(source, None, "the file grew past the size limit while read", "try again")
    return data


def decode_lines(data: bytes | str, source: str) -> list[str]:
    """The file's lines (any of CRLF, CR, LF ends a line), decoded as every LightInv text
    file is (``lightinv_core.textcodec``: UTF-16 with or without a byte-order mark,
    UTF-8, else Latin-1).

    Refuses binary data (NUL bytes) and empty files with the line where it shows."""
    text = decode_text(data)[0] if isinstance(data, bytes) else data
    text = text.removeprefix("\ufeff")
    nul = text.find("\0")
    if nul >= 0:
        line = text.count("\n", 0, nul) + 1
        raise fail(source, line, "binary data (NUL bytes), not a text file", "check the file")
    lines = _LINE_BREAK.split(text)
    if len(lines) > 1 and not lines[-1]:
        lines.pop()  # the break ends the last line; it does not start another
    if not any(line.strip() for line in lines):
        raise fail(source, 1, "the file is empty", "export the photometric file again")
    return lines


def parse_number(token: str) -> float | None:
    """A plain decimal number (no nan, inf, hex or underscores), or None."""
    if not _NUMBER.fullmatch(token):
        return None
    value = float(token)
    return value if np.isfinite(value) else None


class Tokens:
    """The numbers of a file from one line on, in order, each with its line number.

    ``separators`` is a regex of what splits numbers (IES: whitespace and commas;
    EULUMDAT: whitespace, with a comma read as a decimal point)."""

    def __init__(
        self,
        lines: list[str],
        start: int,
        source: str,
        separators: str = r"[\s,\x1a]+",
        decimal_comma: bool = False,
    ) -> None:
        self._lines = lines
        self._next = start  # index of the next line to split
        self._cur: list[str] = []
        self._pos = 0
        self._line = start  # 1-based number of the line of _cur
        self._split = re.compile(separators)
        self._comma = decimal_comma
        self.source = source
        last = len(lines)
        while last > 1 and not lines[last - 1].strip():
            last -= 1
        self.last_line = last

    def _fill(self) -> bool:
        while self._pos >= len(self._cur):
            if self._next >= len(self._lines):
                return False
            self._cur = [t for t in self._split.split(self._lines[self._next]) if t]
            self._pos = 0
            self._next += 1
            self._line = self._next
        return True

    def take(self, n: int, what: str) -> tuple[list[str], list[int]]:
        """The next ``n`` tokens and their line numbers; an error if the file ends."""
        toks: list[str] = []
        lines: list[int] = []
        while len(toks) < n:
            if not self._fill():
                where = f"before the {what}" if n == 1 else f"after {len(toks)} of {n} {what}"
                raise fail(
                    self.source,
                    self.last_line,
                    f"the file ends {where}",
                    "the file is truncated: export it again",
                )
            k = min(n - len(toks), len(self._cur) - self._pos)
            toks.extend(self._cur[self._pos : self._pos + k])
            lines.extend([self._line] * k)
            self._pos += k
        return toks, lines

    def numbers(self, n: int, what: str) -> tuple[np.ndarray, list[int]]:
        """The next ``n`` tokens as finite floats, with their line numbers."""
        toks, lines = self.take(n, what)
        if self._comma:
            toks = [t.replace(",", ".") for t in toks]
        values = np.empty(n)
        for k, tok in enumerate(toks):
            v = parse_number(tok)
            if v is None:
                # A number too large for a float (1e999) is as wrong as text here.
                kind = "too large" if _NUMBER.fullmatch(tok) else "not a number"
                raise fail(
                    self.source,
                    lines[k],
                    f"{what}: {quote(tok)} is {kind}",
                    "fix or export the file again",
                )
            values[k] = v
        return values, lines

    def number(self, what: str) -> tuple[float, int]:
        values, lines = self.numbers(1, what)
        return float(values[0]), lines[0]

    def integer(self, what: str, lo: int, hi: int) -> tuple[int, int]:
        """The next token as a whole number within [lo, hi] ("2" or "2.0")."""
        value, line = self.number(what)
        if value != int(value) or not lo <= value <= hi:
            raise fail(
                self.source,
                line,
                f"{what} is {value:g}",
                f"it must be a whole number from {lo} to {hi}",
            )
        return int(value), line

    def expect_end(self, after: str) -> None:
        """An error if anything but whitespace follows."""
        if self._fill():
            tok = self._cur[self._pos]
            raise fail(
                self.source,
                self._line,
                f"unexpected {quote(tok)} after {after}",
                "too many values: check the angle counts in the header",
            )


def check_angles(
    source: str, values: np.ndarray, lines: list[int], what: str, lo: float, hi: float
) -> None:
    """Angles strictly increasing within [lo, hi] (degrees), else an error at the line."""
    for k, v in enumerate(values):
        if not lo <= v <= hi:
            raise fail(source, lines[k], f"{what} {v:g} is outside {lo:g}..{hi:g}", "fix the angle")
        if k and v <= values[k - 1]:
            raise fail(
                source,
                lines[k],
                f"{what} {v:g} does not increase (after {values[k - 1]:g})",
                "list the angles in increasing order",
            )


def check_intensities(
    source: str, values: np.ndarray, lines: list[int], what: str = "intensity"
) -> None:
    """Intensities >= 0, else an error at the first negative one's line."""
    bad = np.nonzero(values < 0)[0]
    if bad.size:
        k = int(bad[0])
        raise fail(
            source,
            lines[k],
            f"negative {what} {values[k]:g}",
            "intensities must be >= 0: fix or export the file again",
        )


def check_candela(source: str, values: np.ndarray, factor: float, lines: list[int]) -> None:
    """Intensities in cd (the file's values times its multipliers ``factor``) at most
    MAX_CANDELA, else an error at the line of the first too large one."""
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is caught just below
        candela = values * factor
    bad = np.nonzero(~(candela <= MAX_CANDELA))[0]
    if bad.size:
        k = int(bad[0])
        raise fail(
            source,
            lines[k],
            f"an intensity of {candela[k]:.3g} cd (with the file's multipliers) is absurd",
            f"check the value and the multipliers (at most {MAX_CANDELA:g} cd)",
        )


def fmt_number(value: float, digits: int = 7) -> str:
    """A number as the writers print it: ``digits`` significant digits, never '-0'."""
    text = format(float(value) + 0.0, f".{digits}g")
    return "0" if text == "-0" else text


def one_line(text: str, limit: int | None = None) -> str:
    """A header text field: whitespace runs (line breaks too) become one space."""
    out = " ".join(str(text).split())
    return out[:limit] if limit else out
