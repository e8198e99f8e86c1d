"""Scenes as pictures in Jupyter: a small render, flattened, sRGB-encoded, as PNG bytes."""
import struct
import zlib

import numpy as np

# The longest side of the picture Jupyter shows: a quick look, not the final render.
PREVIEW_SIZE = 320


def srgb(linear: np.ndarray) -> np.ndarray:
    """IEC 61966-2-1's encoding of linear values in [0, 1], as the PNG writer applies it."""
    v = np.clip(linear, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def png_bytes(rgb: np.ndarray) -> bytes:
    """An 8-bit RGB PNG of linear `rgb` (height, width, 3)."""
    pixels = np.floor(srgb(rgb) * 255 + 0.5).astype(np.uint8)
    height, width = pixels.shape[:2]
    rows = b"".join(b"\x00" + pixels[y].tobytes() for y in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"sRGB", b"\x00") +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def preview_size(width: int, height: int) -> tuple:
    """The scene's size scaled down (never up) so that its longer side is at most PREVIEW_SIZE."""
    scale = min(1.0, PREVIEW_SIZE / max(width, height))
    return max(1, round(width * scale)), max(1, round(height * scale))
