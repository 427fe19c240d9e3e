"""What a file that should be text is, when it is not: one clean line instead of its bytes.

Every reader of a user's text file (laboratory records, the project's CSV, protocols) calls
:func:`check_text` on the file's first bytes before it decodes them, so that a compressed file
or UTF-16 text is named as such ("FILE is gzip-compressed: decompress it first") instead of
being read as Latin-1 and reported with NUL and binary bytes in the message.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["check_text", "check_text_file", "HEAD_BYTES"]

HEAD_BYTES = 4096
"""How much of a file's start is looked at."""

# magic numbers of the compressed and archive formats a record might come in
_COMPRESSED: tuple[tuple[bytes, str], ...] = (
    (b"\x1f\x8b", "gzip-compressed: decompress it first (gunzip)"),
    (b"BZh", "bzip2-compressed: decompress it first (bunzip2)"),
    (b"\xfd7zXZ\x00", "xz-compressed: decompress it first (unxz)"),
    (b"\x28\xb5\x2f\xfd", "zstd-compressed: decompress it first (unzstd)"),
    (b"PK\x03\x04", "a zip archive: extract the text file from it first"),
    (b"7z\xbc\xaf\x27\x1c", "a 7z archive: extract the text file from it first"),
    (b"%PDF", "a PDF document: export the data as a text table"),
    (b"\xd0\xcf\x11\xe0", "an old Excel/Office file: save the sheet as CSV or tab-separated "
                          "text"),
)


def check_text(head: bytes, source: str) -> None:
    """Refuse bytes that are not UTF-8 or Latin-1 text, naming what they are.

    Parameters
    ----------
    head : bytes
        The first bytes of the file (:data:`HEAD_BYTES` are enough).
    source : str
        The file's name, for the message.

    Raises
    ------
    ValueError
        ``SOURCE is gzip-compressed: decompress it first`` (bzip2, xz, zstd, zip, 7z, PDF,
        Office), ``SOURCE is UTF-16 text: save it as UTF-8``, ``... UTF-32 ...``, or ``SOURCE
        is not a text file (NUL bytes): ...``.
    """
    for magic, what in _COMPRESSED:
        if head.startswith(magic):
            raise ValueError(f"{source} is {what}")
    if head.startswith((b"\xff\xfe\x00\x00", b"\x00\x00\xfe\xff")):
        raise ValueError(f"{source} is UTF-32 text: save it as UTF-8")
    if head.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise ValueError(f"{source} is UTF-16 text: save it as UTF-8")
    if b"\x00" in head:
        # UTF-16 without its byte-order mark: every other byte of ASCII text is NUL
        even, odd = head[0::2], head[1::2]
        if len(head) >= 16 and (even.count(0) > 0.4 * len(even) or odd.count(0) > 0.4 * len(odd)):
            raise ValueError(f"{source} is UTF-16 text: save it as UTF-8")
        raise ValueError(f"{source} is not a text file (it holds NUL bytes): give a text "
                         "table, tab- or comma-separated")


def check_text_file(path: str | os.PathLike[str]) -> None:
    """:func:`check_text` on the first :data:`HEAD_BYTES` of ``path`` (an unreadable file is
    left to the reader, which names the error)."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(HEAD_BYTES)
    except OSError:
        return
    check_text(head, str(Path(path)))
