"""The pages of a PDF's outline entries (boundary): which page each heading of a printed report
landed on, read from the document outline (bookmarks) headless Chromium writes with
``generateDocumentOutline``, so that the contents list can show page numbers.

Only what Chromium's PDF writer (Skia) produces is read: uncompressed object dictionaries, the
page tree from the catalogue's ``/Pages``, outline items with ``/Title`` (a literal or a
UTF-16 hex string) and an explicit ``/Dest [page 0 R ...]``. Anything else reads as no pages
(the contents list then shows none): this is a convenience, not a PDF parser.
"""

from __future__ import annotations

import re

__all__ = ["heading_pages"]

_OBJ = re.compile(rb"(\d+) 0 obj\s*<<(.*?)>>\s*(?:endobj|stream)", re.S)
_KIDS = re.compile(rb"/Kids\s*\[([^\]]*)\]")
_REF = re.compile(rb"(\d+) 0 R")
_TITLE = re.compile(rb"/Title\s*(\((?:\\.|[^\\)])*\)|<[0-9A-Fa-f\s]*>)", re.S)
_DEST = re.compile(rb"/Dest\s*\[\s*(\d+) 0 R")
_ESCAPES = {b"n": b"\n", b"r": b"\r", b"t": b"\t", b"b": b"\b", b"f": b"\f"}


def _literal(raw: bytes) -> bytes:
    """The bytes of a PDF literal string ``(...)`` (escapes and octal codes resolved)."""
    out = bytearray()
    i, body = 0, raw[1:-1]
    while i < len(body):
        c = body[i : i + 1]
        if c != b"\\":
            out += c
            i += 1
            continue
        nxt = body[i + 1 : i + 2]
        octal = re.match(rb"[0-7]{1,3}", body[i + 1 : i + 4])
        if octal:
            out.append(int(octal.group(), 8) & 0xFF)
            i += 1 + len(octal.group())
        else:
            out += _ESCAPES.get(nxt, nxt)
            i += 2
    return bytes(out)


def _text(raw: bytes) -> str:
    """A PDF text string: UTF-16 with its byte-order mark, else PDFDocEncoding (as Latin-1)."""
    data = (
        bytes.fromhex(re.sub(rb"\s", b"", raw[1:-1]).decode()) if raw[:1] == b"<" else _literal(raw)
    )
    if data[:2] == b"\xfe\xff":
        return data[2:].decode("utf-16-be", errors="replace")
    return data.decode("latin-1")


def heading_pages(pdf: bytes) -> dict[str, int]:
    """The page (from 1) of every outline entry of a PDF, by its title.

    Parameters
    ----------
    pdf : bytes
        The PDF file's contents.

    Returns
    -------
    dict of str to int
        {title with its white space collapsed: page number}, the first entry of a title
        winning; empty when the file has no outline this reader understands.

    Examples
    --------
    >>> doc = (b"1 0 obj <</Type /Catalog /Pages 2 0 R>> endobj "
    ...        b"2 0 obj <</Type /Pages /Kids [3 0 R 4 0 R] /Count 2>> endobj "
    ...        b"3 0 obj <</Type /Page>> endobj 4 0 obj <</Type /Page>> endobj "
    ...        b"5 0 obj <</Title (2 Verdict table) /Dest [4 0 R /XYZ 0 0 0]>> endobj")
    >>> heading_pages(doc)
    {'2 Verdict table': 2}
    """
    objects = {int(m.group(1)): m.group(2) for m in _OBJ.finditer(pdf)}
    catalog = next((d for d in objects.values() if re.search(rb"/Type\s*/Catalog", d)), None)
    root = re.search(rb"/Pages\s+(\d+) 0 R", catalog) if catalog is not None else None
    if root is None:
        return {}
    order: list[int] = []
    stack = [int(root.group(1))]
    seen: set[int] = set()
    while stack:  # depth first, kids in order: the pages in reading order
        number = stack.pop()
        if number in seen or number not in objects:
            continue
        seen.add(number)
        kids = _KIDS.search(objects[number])
        if kids is None:
            order.append(number)
            continue
        stack.extend(reversed([int(r) for r in _REF.findall(kids.group(1))]))
    page = {number: i + 1 for i, number in enumerate(order)}
    out: dict[str, int] = {}
    for body in objects.values():
        title, dest = _TITLE.search(body), _DEST.search(body)
        if title is None or dest is None or int(dest.group(1)) not in page:
            continue
        out.setdefault(" ".join(_text(title.group(1)).split()), page[int(dest.group(1))])
    return out
