#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The cohort workflow on a small cohort made from ../shared/data and phantoms, one subject broken:
# every good subject done, the broken one listed with its exit code, the table and the HTML page written,
# a second run does nothing, a touched input redoes only its subject, and the page renders in headless
# Chromium with one picture per good subject.
# usage: test_cohort.sh CONTOUR4D_BINARY     (exit 77, skipped: snakemake missing)
#        C4D_COHORT_KEEP=DIR keeps the results, the screenshot and the logs in DIR.
set -euo pipefail
c4d=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
command -v snakemake > /dev/null || { echo "snakemake missing (scripts/setup.sh installs it): skipped"; exit 77; }
command -v chromium > /dev/null || { echo "FAIL: chromium missing (scripts/setup.sh installs it)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

/usr/bin/python3 "$repo/workflows/cohort/make_demo_cohort.py" "$work/cohort" --contour4d "$c4d"
run() {
  (cd "$work" && snakemake -s "$repo/workflows/cohort/Snakefile" --cores 2 \
     --config subjects="$work/cohort/subjects.csv" results="$work/results" contour4d="$c4d" "$@")
}
start=$(date +%s%N)
run > "$work/run1.log" 2>&1 || { tail -40 "$work/run1.log"; fail "the workflow failed"; }
ms=$(( ($(date +%s%N) - start) / 1000000 ))
run -n > "$work/run2.log" 2>&1
grep -q "Nothing to be done" "$work/run2.log" || { cat "$work/run2.log"; fail "a second run would do work"; }
# a changed input redoes that subject (its steps and the cohort table) and nothing else
touch "$work/cohort/inputs/bifurcation/contours.json"
run -n > "$work/run3.log" 2>&1
redo=$(grep -o "subject=[^,]*" "$work/run3.log" | sort -u | tr '\n' ' ')
[ "$redo" = "subject=phantom-bifurcation " ] || { cat "$work/run3.log"; fail "a touched input redoes: $redo"; }
grep -q "^cohort *1 " "$work/run3.log" || fail "a touched input does not redo the cohort table"

/usr/bin/python3 - "$work/results" "$ms" <<'PY'
import csv, json, os, sys
res = sys.argv[1]
rows = list(csv.DictReader(open(f"{res}/cohort.csv")))
good = [r for r in rows if r["exit_code"] == "0"]
bad = [r for r in rows if r["exit_code"] != "0"]
subjects = {r["subject"] for r in rows}
assert len(subjects) >= 6, rows
assert [(r["subject"], r["exit_code"], r["failed_step"]) for r in bad] == [("broken-truncated", "12", "extract")], bad
assert "JSON ends early" in bad[0]["message"], bad[0]
for r in rows:
    unit = f"{res}/{r['subject']}/{r['structure']}"
    status = json.load(open(f"{unit}/status.json"))
    assert str(status["exit_code"]) == r["exit_code"] and os.path.getsize(f"{unit}/log.txt") > 0, unit
for r in good:
    unit = f"{res}/{r['subject']}/{r['structure']}"
    for f in ("mesh/report.json", "mesh/mesh.pvd", "evaluation.json", "model.c4d", "model.glb"):
        assert os.path.exists(f"{unit}/{f}"), f"{unit}/{f}"
    assert float(r["edv_ml"]) > 0 and r["correspondence"] == "True", r
    assert float(r["angles_40_80_pct_min"]) > 80, r
wall = [r for r in good if r["structure"] == "lv-wall"]
assert wall and 40 < float(wall[0]["wall_mass_g"]) < 400, wall
page = open(f"{res}/cohort.html").read()
good_subjects = {r["subject"] for r in good}
assert page.count('<img class="curve"') == len(good_subjects), (page.count("<img"), good_subjects)
assert all(f"volume curve of {s}" in page for s in good_subjects)
assert "broken-truncated" in page and "<td>12</td>" in page
seconds = float(sys.argv[2]) / 1000
print(f"cohort: {len(good)} done, {len(bad)} failed as expected; {len(rows)} subject-structures of "
      f"{len(subjects)} subjects in {seconds:.1f} s at --cores 2 ({len(subjects) / seconds * 3600:.0f} subjects per hour)")
for r in rows:
    print(f"  {r['subject']:22s} {r['structure']:8s} exit {r['exit_code']:>2s}  {float(r['seconds']):6.2f} s")
PY

timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,1600 \
  --screenshot="$work/page.png" "file://$work/results/cohort.html" > "$work/chromium.log" 2>&1 || true
[ -s "$work/page.png" ] || { cat "$work/chromium.log"; fail "no screenshot"; }
/usr/bin/python3 - "$work/page.png" <<'PY'
import os, sys
from PIL import Image
img = Image.open(sys.argv[1]).convert("RGB")
assert img.size == (1200, 1600), img.size
colours = img.getcolors(maxcolors=1 << 20)
ink = sum(n for n, c in colours if c != (255, 255, 255)) / (img.size[0] * img.size[1])
blue = sum(n for n, (r, g, b) in colours if b > 150 and r < 80)  # the volume curves (matplotlib's first colour)
assert os.path.getsize(sys.argv[1]) > 20000 and len(colours) > 50 and ink > 0.03 and blue > 500, (len(colours), ink, blue)
print(f"screenshot: {len(colours)} colours, {ink:.1%} not white, {blue} curve pixels")
PY
if [ -n "${C4D_COHORT_KEEP:-}" ]; then
  mkdir -p "$C4D_COHORT_KEEP" && cp -r "$work/results" "$work/page.png" "$work"/run*.log "$C4D_COHORT_KEEP/"
fi
echo "1 passed, 0 failed"
