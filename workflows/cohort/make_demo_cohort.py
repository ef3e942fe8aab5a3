#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A small cohort from the bundled data and phantoms, one subject deliberately broken, for the README's
"many patients" command and the CI test.

usage: make_demo_cohort.py OUT [--contour4d BINARY] [--data ../shared/data]

Writes OUT/subjects.csv and OUT/inputs/: Sunnybrook SC-HF-I-1 (endocardium; and the myocardial wall from both
contour sets), biv-me patient1's LV endocardium cut to three frames (40 ms apart in the study), three phantoms,
and a truncated contour file (exit code 12).
"""
import argparse
import csv
import json
import os
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def run(*cmd):
    subprocess.run([str(c) for c in cmd], check=True, capture_output=True)


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
    rows = [
        {"subject": "sunnybrook-hf1", "input": str(data / "sunnybrook-SC-HF-I-1"), "structures": "lv-endo"},
        {"subject": "sunnybrook-hf1-wall", "input": str(data / "sunnybrook-SC-HF-I-1"), "structures": "lv-wall",
         "args": "--contours both"},
    ]
    # biv-me patient1, three frames of 25 (0, 8, 16: 320 ms apart at the study's 40 ms)
    bivme = inputs / "bivme-patient1-3frames.json"
    run(a.contour4d, "extract", data / "bivme-patient1" / "guidepoints", "-o", bivme)
    doc = json.loads(bivme.read_text())
    doc["frames"] = [dict(doc["frames"][f], time_ms=40.0 * f) for f in (0, 8, 16)]
    bivme.write_text(json.dumps(doc))
    rows.append({"subject": "bivme-patient1", "input": str(bivme), "structures": "lv-endo"})
    for name, extra in (("left-heart", []), ("ellipsoid", ["--frames", "6"]), ("bifurcation", ["--frames", "4"])):
        run(a.contour4d, "phantom", name, "-o", inputs / name, *extra)
        rows.append({"subject": f"phantom-{name}", "input": str(inputs / name / "contours.json"), "structures": "",
                     "frame_ms": "100"})
    broken = inputs / "broken.json"
    text = (inputs / "left-heart" / "contours.json").read_text()
    broken.write_text(text[: len(text) // 2])  # cut in the middle: exit code 12 (parse error)
    rows.append({"subject": "broken-truncated", "input": str(broken), "structures": ""})
    with open(out / "subjects.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["subject", "input", "structures", "frame_ms", "args", "reconstruct_args"])
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows)} subjects in {out / 'subjects.csv'}")


if __name__ == "__main__":
    main()
