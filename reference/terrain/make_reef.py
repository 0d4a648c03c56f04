#!/usr/bin/env python3
"""Writes reef.png: the relief of reference/scenes/shallow_reef.toml, a 256x256 16-bit
grayscale PNG (standard library only; deterministic). Sample v in [0, 1] maps onto the scene's
height_range_m = [-1.5, 3.0] m above the floor's plane (4 m down): coral heads 1-3 m tall
scattered over a rippled sand flat, cut by a sand channel 1.5 m deep.

Run from this folder: python3 make_reef.py
"""
import math
import struct
import zlib

N = 256
EXTENT_M = 120.0
LO, HI = -1.5, 3.0
state = 20261203


def rand():
    """A 32-bit LCG in [0, 1): the same numbers on every machine."""
    global state
    state = (1664525 * state + 1013904223) & 0xFFFFFFFF
    return state / 2**32


heads = []
for _ in range(70):
    x, z = (rand() - 0.5) * EXTENT_M, (rand() - 0.5) * EXTENT_M
    heads.append((x, z, 1.0 + 2.0 * rand(), 1.5 + 3.5 * rand()))


def height(x, z):
    # The channel winds along z, away from the camera at the scene's default view.
    centre = 12.0 * math.sin(z / 23.0) + 4.0
    channel = -1.5 * math.exp(-((x - centre) / 5.0) ** 2)
    ripples = 0.06 * math.sin(0.9 * x + 0.4 * z) + 0.04 * math.sin(1.7 * z - 0.3 * x)
    coral = 0.0
    for hx, hz, tall, radius in heads:
        d2 = ((x - hx) ** 2 + (z - hz) ** 2) / radius**2
        if d2 < 9.0:
            # Flat-topped heads: a squashed Gaussian, rough on top.
            bump = tall * min(1.0, 1.4 * math.exp(-d2))
            coral = max(coral, bump * (1.0 + 0.08 * math.sin(3.1 * x) * math.sin(2.7 * z)))
    return max(channel + ripples + coral * (1.0 + channel / 3.0), LO)


rows = []
for j in range(N):
    z = -0.5 * EXTENT_M + j * EXTENT_M / (N - 1)
    row = bytearray([0])  # filter: none
    for i in range(N):
        x = -0.5 * EXTENT_M + i * EXTENT_M / (N - 1)
        v = (height(x, z) - LO) / (HI - LO)
        row += struct.pack(">H", round(min(max(v, 0.0), 1.0) * 65535))
    rows.append(bytes(row))


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


png = b"\x89PNG\r\n\x1a\n"
png += chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 16, 0, 0, 0, 0))  # 16-bit grayscale
png += chunk(b"IDAT", zlib.compress(b"".join(rows), 9))
png += chunk(b"IEND", b"")
with open("reef.png", "wb") as f:
    f.write(png)
