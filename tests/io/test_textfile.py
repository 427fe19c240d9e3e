"""What a file that should be text is (io/textfile.py), for each encoding and magic number on
its own, both byte orders (issue 25: one encoding tested hides a check in the wrong order).
Each case names the mistake it is for; each was seen failing with it applied."""

from __future__ import annotations

import bz2
import gzip

import pytest

from dryfriction.io.textfile import check_text

TEXT = "Time (s)\tDispl (um)\tFriction\n0.0\t1.5\t0.61\n0.1\t1.6\t0.62\n" * 4


@pytest.mark.parametrize("data, words", [
    # the UTF-32 test after the UTF-16 one (a UTF-32 LE mark starts with UTF-16's)
    (TEXT.encode("utf-32"), "is UTF-32 text"),
    (b"\x00\x00\xfe\xff" + TEXT.encode("utf-32-be"), "is UTF-32 text"),
    (TEXT.encode("utf-16-be"), "is UTF-16 text"),  # no mark: the even bytes NUL
    (TEXT.encode("utf-16-le"), "is UTF-16 text"),  # no mark: the odd bytes NUL
    # mtime=0: the header holds no time, so the test's id is the same in every process (the
    # parallel suite's workers must collect the same tests)
    (gzip.compress(TEXT.encode(), mtime=0), "is gzip-compressed"),
    (bz2.compress(TEXT.encode()), "is bzip2-compressed"),
    (b"%PDF-1.7\n" + TEXT.encode(), "is a PDF document"),
    (TEXT.encode()[:40] + b"\x00" + TEXT.encode()[40:], "is not a text file (it holds NUL"),
])
def test_each_kind_is_named(data: bytes, words: str) -> None:
    with pytest.raises(ValueError) as err:
        check_text(data[:4096], "rec.txt")
    assert str(err.value).startswith(f"rec.txt {words}") and "\n" not in str(err.value)


@pytest.mark.parametrize("encoding", ["utf-8", "latin-1", "utf-8-sig"])
def test_text_passes(encoding: str) -> None:
    check_text(("Temps (µs)\tDéplacement\n" + TEXT).encode(encoding), "rec.txt")
