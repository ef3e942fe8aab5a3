#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The include order of docs/architecture.md, checked on every #include of the library.

A file of folder X (src/X/ or include/contour4d/X/) may include contour4d/Y/... only where Y is X or lies below
X in the layer list that docs/architecture.md gives ("Layers, lowest first: ..."). A private header (one under
src/) is included only from its own folder, by its bare name. apps/, python/, bench/ and tests/ may include any
public header and no private one, except a white-box test (tests/unit/*_internal_test.cpp), which may include
private headers as "<folder>/<name>_internal.h" (src/ is on its include path). src/simd/ is the one place of
hand-written SIMD: it has no public headers, any library folder may include its private headers as
"simd/<name>_internal.h", and no file outside it includes an intrinsics header (<immintrin.h>, <emmintrin.h>, ...).

usage: check_includes.py REPO_ROOT   (exit 1 listing every wrong include)
"""
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
INTRINSICS = re.compile(r'^\s*#\s*include\s+<((?:[a-z]*mmintrin|arm_neon|arm_sve)\.h)>', re.M)
SIMD = "simd"


def layers(root):
    text = (root / "docs" / "architecture.md").read_text()
    m = re.search(r"Layers, lowest first:\s*(.+)", text)
    if not m:
        sys.exit("docs/architecture.md has no line 'Layers, lowest first: core, io, ...'")
    return [name.strip(" `.") for name in m.group(1).split(",")]


def folder_of(root, path):
    """The library folder a file belongs to, or None for apps/, python/, bench/ and tests/."""
    rel = path.relative_to(root).parts
    if rel[0] == "src" and len(rel) > 2:
        return rel[1]
    if rel[:2] == ("include", "contour4d") and len(rel) > 3:
        return rel[2]
    return None


def is_white_box(root, path, target):
    """A white-box test including a private header of a library folder by "<folder>/<name>_internal.h"."""
    parts = target.split("/")
    return (path.name.endswith("_internal_test.cpp") and path.relative_to(root).parts[:2] == ("tests", "unit")
            and len(parts) == 2 and target.endswith("_internal.h") and (root / "src" / target).exists())


def is_simd_kernel(root, own, target):
    """A library folder including one of src/simd/'s private headers by "simd/<name>_internal.h"."""
    parts = target.split("/")
    return (own is not None and len(parts) == 2 and parts[0] == SIMD and target.endswith("_internal.h")
            and (root / "src" / target).exists())


def faults_of(root, path, rank):
    own = folder_of(root, path)
    faults = []
    text = path.read_text(errors="replace")
    if own != SIMD:
        for header in INTRINSICS.findall(text):
            faults.append(f"{path.relative_to(root)}: #include <{header}>: hand-written SIMD lives in src/{SIMD}/ only")
    for target in INCLUDE.findall(text):
        where = f"{path.relative_to(root)}: #include \"{target}\""
        if target.startswith("contour4d/"):
            parts = target.split("/")
            other = parts[1] if len(parts) > 2 else None
            if other is None or other not in rank:
                faults.append(f"{where}: contour4d/{other} is no folder of docs/architecture.md's layers")
            elif own is not None and rank[other] > rank[own]:
                faults.append(f"{where}: {own} may not include {other}, a layer above it")
        elif own is None and is_white_box(root, path, target):
            continue
        elif is_simd_kernel(root, own, target):
            continue
        elif "/" in target or target.startswith(".."):
            faults.append(f"{where}: reaches into another folder's private headers")
        elif own is None and target.endswith("_internal.h"):
            faults.append(f"{where}: a private header of the library")
        elif own is not None and not (path.parent / target).exists():
            faults.append(f"{where}: no such header in {own}'s own folder")
    return faults


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    order = layers(root)
    rank = {name: i for i, name in enumerate(order)}
    missing = [d.name for d in (root / "src").iterdir() if d.is_dir() and d.name not in rank]
    faults = [f"src/{name}: a folder missing from docs/architecture.md's layers" for name in missing]
    if (root / "include" / "contour4d" / SIMD).exists():
        faults.append(f"include/contour4d/{SIMD}: {SIMD} has no public headers (SIMD stays private)")
    files = [p for top in ("src", "include", "apps", "python", "bench", "tests")
             for p in sorted((root / top).rglob("*"))
             if p.suffix in (".h", ".hpp", ".cpp", ".cc") and "wrong_tree" not in p.relative_to(root).parts]  # this test's own fixture
    for path in files:
        faults += faults_of(root, path, rank)
    for f in faults:
        print(f)
    print(f"check_includes: {len(files)} files, layers {' < '.join(order)}: {len(faults)} wrong include(s)")
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main())
