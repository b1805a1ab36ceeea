"""Checks figures: python3 png_check.py WIDTH HEIGHT MIN_BYTES FILE...

Each FILE must be a PNG of WIDTH x HEIGHT pixels, at least MIN_BYTES long, whose middle (the plot
area) shows data: several colours, and enough coloured pixels (the figures draw data in colour;
axes, grid and text are grey or black, so empty axes have none). One line per file; exit status 1
when any fails.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import numpy  # noqa: E402

MIN_COLOURS = 3  # not a blank image (one bar filling the middle has about 7)
MIN_COLOURED = 500  # pixels with a hue: a data line across the middle has well over a thousand


def check(path, width, height, min_bytes):
    size = os.path.getsize(path)
    image = matplotlib.image.imread(path)
    h, w = image.shape[:2]
    middle = image[h // 5: h * 4 // 5, w // 5: w * 4 // 5, :3]
    pixels = (middle.reshape(-1, 3) * 255).astype(numpy.uint8)
    colours = len(numpy.unique(pixels, axis=0))
    spread = pixels.max(axis=1).astype(int) - pixels.min(axis=1).astype(int)
    coloured = int(numpy.count_nonzero(spread > 60))
    good = size >= min_bytes and (w, h) == (width, height) and colours >= MIN_COLOURS and coloured >= MIN_COLOURED
    print(f"{'ok' if good else 'BAD'} {path}: {size} bytes, {w}x{h}, {colours} colours, "
          f"{coloured} coloured pixels in the middle")
    return good


def main():
    width, height, min_bytes = (int(a) for a in sys.argv[1:4])
    results = [check(p, width, height, min_bytes) for p in sys.argv[4:]]
    return 0 if results and all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
