#!/usr/bin/python3
"""Compares two folders of PNG frames image by image.

    compare_pngs.py DIR_A DIR_B MAX_MEAN

Both folders must hold the same frame_NNN.png names; for each pair the mean absolute grey-level difference
(0-255) is printed. Exits non-zero when a folder is empty, the names differ, or a mean reaches MAX_MEAN.
"""
import os
import sys

import numpy as np
from PIL import Image


def grey(path):
    return np.asarray(Image.open(path).convert("L"), dtype=float)


def main():
    a, b, limit = sys.argv[1], sys.argv[2], float(sys.argv[3])
    names = sorted(n for n in os.listdir(a) if n.endswith(".png"))
    if not names or names != sorted(n for n in os.listdir(b) if n.endswith(".png")):
        sys.exit(f"{a} and {b} do not hold the same PNG frames")
    means = [float(np.abs(grey(os.path.join(a, n)) - grey(os.path.join(b, n))).mean()) for n in names]
    print("mean grey differences:", " ".join(f"{m:.3f}" for m in means))
    if max(means) >= limit:
        sys.exit(f"a mean difference reaches {limit}")


if __name__ == "__main__":
    main()
