#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The cohort workflow on a small cohort made from ../shared/data and phantoms, one subject broken:
# every good subject done, the broken one listed with its exit code, the table and the HTML page written,
# a second run does nothing, and the page renders in headless Chromium with one picture per good subject.
# usage: test_cohort.sh CONTOUR4D_BINARY     (exit 77: snakemake or chromium missing, skipped)
set -euo pipefail
c4d=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
command -v snakemake > /dev/null || { echo "snakemake missing (scripts/setup.sh installs it)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

/usr/bin/python3 "$repo/workflows/cohort/make_demo_cohort.py" "$work/cohort" --contour4d "$c4d"
run() {
  (cd "$work" && snakemake -s "$repo/workflows/cohort/Snakefile" --cores 2 \
     --config subjects="$work/cohort/subjects.csv" results="$work/results" contour4d="$c4d" "$@")
}
start=$(date +%s%N)
run > "$work/run1.log" 2>&1 || { tail -40 "$work/run1.log"; echo "FAIL: the workflow failed"; exit 1; }
seconds=$(( ($(date +%s%N) - start) / 1000000 ))  # ms
run > "$work/run2.log" 2>&1
grep -q "Nothing to be done" "$work/run2.log" || { cat "$work/run2.log"; echo "FAIL: a second run did work"; exit 1; }

/usr/bin/python3 - "$work/results" "$seconds" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/cohort.csv")))
good = [r for r in rows if r["exit_code"] == "0"]
bad = [r for r in rows if r["exit_code"] != "0"]
assert len(rows) >= 6, rows
assert [(r["subject"], r["exit_code"], r["failed_step"]) for r in bad] == [("broken-truncated", "12", "extract")], bad
for r in good:
    assert float(r["edv_ml"]) > 0 and r["correspondence"] == "True", r
    assert float(r["angles_40_80_pct_min"]) > 80, r
wall = [r for r in good if r["structure"] == "lv-wall"]
assert wall and 40 < float(wall[0]["wall_mass_g"]) < 400, wall
html = open(f"{sys.argv[1]}/cohort.html").read()
assert html.count('<svg class="curve"') == len(good), html.count("<svg")
assert "broken-truncated" in html
units = len(rows)
seconds = float(sys.argv[2]) / 1000
per_hour = units / seconds * 3600
print(f"cohort: {len(good)} done, {len(bad)} failed as expected; {units} subject-structures in {seconds:.1f} s "
      f"at --cores 2 ({per_hour:.0f} per hour)")
PY

if command -v chromium > /dev/null; then
  timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,900 \
    --screenshot="$work/page.png" "file://$work/results/cohort.html" > "$work/chromium.log" 2>&1 || true
  /usr/bin/python3 - "$work/page.png" <<'PY'
import sys
from PIL import Image
img = Image.open(sys.argv[1]).convert("RGB")
assert img.size == (1200, 900), img.size
colours = img.getcolors(maxcolors=1 << 20)
red = sum(n for n, (r, g, b) in colours if r > 150 and g < 90 and b < 90)  # the volume curves' strokes
assert len(colours) > 20 and red > 500, (len(colours), red)
print(f"screenshot: {len(colours)} colours, {red} curve pixels")
PY
else
  echo "chromium missing: the screenshot check is skipped"
fi
echo "1 passed, 0 failed"
