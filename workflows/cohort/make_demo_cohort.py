#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A small cohort from the bundled data and phantoms, one subject deliberately broken, for the README's
"many patients" command and the CI test.

usage: make_demo_cohort.py OUT [--contour4d BINARY] [--data ../shared/data]

Writes OUT/subjects.csv and OUT/inputs/: six subjects, seven subject-structures. Sunnybrook SC-HF-I-1 (the
endocardium, and the myocardial wall from both contour sets), biv-me patient1's LV endocardium cut to three
frames (320 ms apart), two phantoms' contours, a phantom as a 4D NIfTI label image, and a truncated contour file
(exit code 12).
"""
import argparse
import csv
import json
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def run(*cmd):
    subprocess.run([str(c) for c in cmd], check=True, capture_output=True)


def bivme_three_frames(c4d, data, out):
    """biv-me patient1's LV endocardium, frames 0, 8 and 16 of 25 (the study's frames are 40 ms apart)."""
    run(c4d, "extract", data / "bivme-patient1" / "guidepoints", "-o", out)
    doc = json.loads(out.read_text())
    doc["frames"] = [dict(doc["frames"][f], time_ms=40.0 * f) for f in (0, 8, 16)]
    out.write_text(json.dumps(doc))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--contour4d", default=str(REPO / "build" / "apps" / "contour4d" / "contour4d"))
    ap.add_argument("--data", default=str(REPO.parent / "shared" / "data"))
    a = ap.parse_args()
    out = Path(a.out).resolve()
    inputs = out / "inputs"
    inputs.mkdir(parents=True, exist_ok=True)
    data = Path(a.data)
    if not data.is_dir():
        raise SystemExit(f"make_demo_cohort: {data} is missing (../shared/data beside the checkout)")
    rows = [{"subject": "sunnybrook-hf1", "input": str(data / "sunnybrook-SC-HF-I-1"), "structures": "lv-endo lv-wall"}]
    bivme_three_frames(a.contour4d, data, inputs / "bivme-patient1-3frames.json")
    rows.append({"subject": "bivme-patient1", "input": "inputs/bivme-patient1-3frames.json", "structures": "lv-endo"})
    for name, extra in (("left-heart", []), ("bifurcation", ["--frames", "4"])):
        run(a.contour4d, "phantom", name, "-o", inputs / name, *extra)
        rows.append({"subject": f"phantom-{name}", "input": f"inputs/{name}/contours.json"})
    # a label image (NIfTI, 4 frames, no times of its own: frame_ms gives them)
    run(a.contour4d, "phantom", "ellipsoid", "--frames", "4", "--spacing", "8", "-o", inputs / "ellipsoid",
        "--mask", inputs / "ellipsoid" / "mask.nii.gz")
    rows.append({"subject": "mask-ellipsoid", "input": "inputs/ellipsoid/mask.nii.gz", "frame_ms": "50"})
    broken = inputs / "broken.json"
    text = (inputs / "left-heart" / "contours.json").read_text()
    broken.write_text(text[: len(text) // 2])  # cut in the middle: exit code 12 (parse error)
    rows.append({"subject": "broken-truncated", "input": "inputs/broken.json"})
    with open(out / "subjects.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["subject", "input", "structures", "frame_ms", "args", "reconstruct_args"])
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows)} subjects in {out / 'subjects.csv'}")


if __name__ == "__main__":
    main()
