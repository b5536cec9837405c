"""Text files of unknown encoding, as the tools that write them leave them.

One decoder for the text formats LightInv reads (OBJ and MTL models, weather files,
IES and EULUMDAT photometry): UTF-16 with a byte-order mark, or without one when zero
bytes fill every other place (as Windows tools write "Unicode" text), else UTF-8 (a
UTF-8 byte-order mark dropped), else Latin-1, which never fails. A bottom-layer module:
the standard library only, so every layer may use it.
"""

from __future__ import annotations

UTF16_BOMS = (b"\xff\xfe", b"\xfe\xff")
_HEAD = 4096  # bytes looked at to recognise UTF-16 without a byte-order mark


def decode_text(data: bytes) -> tuple[str, str]:
    """(text, encoding) of a file: UTF-16 (with a byte-order mark, or zero bytes in
    every other place, as Windows tools write), else UTF-8, else latin-1 (which never
    fails). ``encoding`` is "utf-16", "utf-16-le", "utf-16-be", "utf-8" or "latin-1".

    UTF-16 that does not decode (an odd length, a lone surrogate) falls through to the
    next rule, so binary data keeps its zero bytes for the caller to refuse."""
    if data[:2] in UTF16_BOMS:
        try:
            return data.decode("utf-16"), "utf-16"
        except UnicodeDecodeError:
            pass
    head = data[:_HEAD]
    if len(head) >= 4 and head.count(0) >= 0.4 * len(head):
        order = "utf-16-le" if head[1::2].count(0) > head[0::2].count(0) else "utf-16-be"
        try:
            return data[: len(data) // 2 * 2].decode(order), order
        except UnicodeDecodeError:
            pass
    try:
        return data.decode("utf-8-sig"), "utf-8"
    except UnicodeDecodeError:
        return data.decode("latin-1"), "latin-1"
