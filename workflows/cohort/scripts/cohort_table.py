#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The cohort table (CSV) and a one-page HTML summary with each subject's volume curve as an inline SVG.

usage: cohort_table.py --csv OUT.csv --html OUT.html UNIT_DIR...

Each UNIT_DIR is RESULTS/<subject>/<structure> with steps/*.json, mesh/report.json and evaluation.json.
"""
import argparse
import csv
import html
import json
import os

STEPS = ("extract", "reconstruct", "evaluate", "pack")
COLUMNS = ["subject", "structure", "exit_code", "failed_step", "message", "frames", "frame_times", "edv_ml", "esv_ml",
           "ef_percent", "ed_frame", "es_frame", "wall_mass_g", "angles_40_80_pct_min", "min_angle_deg",
           "bad_triangles_per_frame", "conformity_mean_mm", "conformity_max_mm", "correspondence", "model_bytes",
           "seconds"]


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def row_of(unit):
    subject, structure = os.path.normpath(unit).split(os.sep)[-2:]
    row = {"subject": subject, "structure": structure, "exit_code": 0, "failed_step": "", "message": "", "seconds": 0.0}
    for step in STEPS:
        st = load(os.path.join(unit, "steps", step + ".json")) or {"exit_code": 1, "message": "no status"}
        row["seconds"] = round(row["seconds"] + st.get("seconds", 0.0), 2)
        if st["exit_code"] != 0 and row["exit_code"] == 0:
            row.update(exit_code=st["exit_code"], failed_step=st.get("failed_step", step), message=st["message"])
    report = load(os.path.join(unit, "mesh", "report.json"))
    volumes = []
    if report and row["exit_code"] == 0:
        s = report["summary"]
        volumes = s["volume_ml"]
        row.update(frames=s["frames"], frame_times=s["frame_times_source"], edv_ml=s["edv_ml"], esv_ml=s["esv_ml"],
                   ef_percent=s["ef_percent"], ed_frame=s["ed_frame"], es_frame=s["es_frame"],
                   correspondence=s["correspondence"])
        if "mass_g" in s:  # the myocardium: its mean mass over the frames
            row["wall_mass_g"] = round(sum(s["mass_g"]) / len(s["mass_g"]), 2)
    ev = load(os.path.join(unit, "evaluation.json"))
    if ev and row["exit_code"] == 0:
        q = ev["summary"]
        row["angles_40_80_pct_min"] = round(min(f["quality"]["angles_40_80_pct"] for f in ev["frames"]), 2)
        row["min_angle_deg"] = round(q["min_angle_deg"], 2)
        row["bad_triangles_per_frame"] = q["bad_triangles_per_frame"]
        if "conformity" in q:
            row["conformity_mean_mm"] = q["conformity"]["mean_of_frame_means_mm"]
            row["conformity_max_mm"] = q["conformity"]["max_mm"]
    model = os.path.join(unit, "model.c4d")
    if os.path.exists(model) and row["exit_code"] == 0:
        row["model_bytes"] = os.path.getsize(model)
    return row, volumes


def svg_curve(volumes, width=260, height=90):
    """The volume curve (ml per frame) as a small inline SVG."""
    if not volumes:
        return ""
    lo, hi = min(volumes), max(volumes)
    span = hi - lo or 1.0
    n = max(len(volumes) - 1, 1)
    pts = " ".join(f"{10 + (width - 20) * i / n:.1f},{height - 15 - (height - 30) * (v - lo) / span:.1f}"
                   for i, v in enumerate(volumes))
    return (f'<svg class="curve" width="{width}" height="{height}" viewBox="0 0 {width} {height}">'
            f'<polyline fill="none" stroke="#c0392b" stroke-width="2" points="{pts}"/>'
            + "".join(f'<circle cx="{p.split(",")[0]}" cy="{p.split(",")[1]}" r="3" fill="#c0392b"/>' for p in pts.split())
            +
            f'<text x="10" y="12" font-size="10">{hi:.1f} ml</text>'
            f'<text x="10" y="{height - 2}" font-size="10">{lo:.1f} ml</text></svg>')


def mass(row):
    return f' · wall {row["wall_mass_g"]:.1f} g' if row.get("wall_mass_g") not in (None, "") else ""


def write_html(path, rows, curves):
    good = [r for r in rows if r["exit_code"] == 0]
    bad = [r for r in rows if r["exit_code"] != 0]
    cards = "".join(
        f'<div class="card"><h3>{html.escape(r["subject"])} · {html.escape(r["structure"])}</h3>{curves[i]}'
        f'<p>EDV {r.get("edv_ml", 0):.1f} ml · ESV {r.get("esv_ml", 0):.1f} ml · EF {r.get("ef_percent", 0):.1f} %'
        f' · {r.get("frames", "")} frames{mass(r)}</p></div>'
        for i, r in enumerate(rows) if r["exit_code"] == 0)
    failures = "".join(f"<tr><td>{html.escape(r['subject'])}</td><td>{html.escape(r['structure'])}</td>"
                       f"<td>{r['failed_step']}</td><td>{r['exit_code']}</td><td>{html.escape(r['message'])}</td></tr>"
                       for r in bad)
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>contour4d cohort</title>
<style>body{{font-family:sans-serif;margin:20px}} .card{{display:inline-block;border:1px solid #ccc;margin:6px;
padding:6px;width:280px;vertical-align:top}} h3{{font-size:14px;margin:2px}} p{{font-size:12px;margin:2px}}
table{{border-collapse:collapse}} td,th{{border:1px solid #ccc;padding:3px 6px;font-size:12px}}</style></head>
<body><h1>contour4d cohort</h1>
<p>{len(good)} of {len(rows)} subject-structures done, {len(bad)} failed. Volume curves: ml per frame.
The table is cohort.csv beside this page.</p>
{cards}
<h2>Failed</h2>
<table><tr><th>subject</th><th>structure</th><th>step</th><th>exit code</th><th>message</th></tr>{failures}</table>
</body></html>
"""
    with open(path + ".tmp", "w") as f:
        f.write(page)
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True)
    ap.add_argument("--html", required=True)
    ap.add_argument("units", nargs="*")
    a = ap.parse_args()
    rows, curves = [], []
    for unit in a.units:
        row, volumes = row_of(unit)
        rows.append(row)
        curves.append(svg_curve(volumes))
    with open(a.csv + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    os.replace(a.csv + ".tmp", a.csv)
    write_html(a.html, rows, curves)


if __name__ == "__main__":
    main()
