"""The bytes of a structure file, plain or gzip, read a chunk at a time with a limit:
one loop for every reader, so that a gzip bomb is refused after ``max_bytes`` and never
held whole."""

from __future__ import annotations

import gzip
import os
import zlib

__all__ = ["CHUNK", "chunks", "too_large"]

#: Bytes read (or decompressed) at a time.
CHUNK = 2**20


def chunks(path, max_bytes: int):
    """Yield ``(chunk, over)``: the file's bytes (decompressed if its first two bytes are
    gzip's), at most :data:`CHUNK` at a time.  When more than ``max_bytes`` have come
    out, the last chunk is cut at the limit, ``over`` is True and nothing more is read:
    the caller decides what to do with the bytes within the limit and raises
    :func:`too_large`.  An unreadable gzip stream raises a ValueError naming the file."""
    name = os.fspath(path)
    with open(path, "rb") as raw:
        gz = raw.read(2) == b"\x1f\x8b"
        raw.seek(0)
        fh = gzip.GzipFile(fileobj=raw, mode="rb") if gz else raw
        total = 0
        while True:
            try:
                chunk = fh.read(min(CHUNK, max_bytes + 1 - total))
            except (OSError, EOFError, zlib.error) as e:
                if not gz:
                    raise
                raise ValueError(f"{name!r} is not a readable gzip file: {e}") from None
            if not chunk:
                return
            total += len(chunk)
            over = total > max_bytes
            if over:
                chunk = chunk[: len(chunk) - (total - max_bytes)]
            yield chunk, over
            if over:
                return


def too_large(path, max_bytes: int, where: str = "") -> ValueError:
    """The error for a file with more than ``max_bytes`` of (decompressed) text;
    ``where`` says where reading would have stopped (e.g. " before its first END")."""
    name = os.fspath(path)
    with open(path, "rb") as raw:
        gz = raw.read(2) == b"\x1f\x8b"
    what = "decompresses to" if gz else "holds"
    return ValueError(
        f"{name!r} {what} more than max_bytes={max_bytes} bytes{where}; pass a larger max_bytes= to read it"
    )
