#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The cohort table (CSV) and a one-page HTML summary: each subject's volume curves as one embedded PNG
(matplotlib, Agg), the failures with their exit codes and messages, and the table.

usage: cohort_table.py --csv OUT.csv --html OUT.html UNIT_DIR...

Each UNIT_DIR is RESULTS/<subject>/<structure> with status.json, mesh/report.json and evaluation.json.
"""
import argparse
import base64
import csv
import html
import io
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after the backend)

COLUMNS = ["subject", "structure", "exit_code", "failed_step", "message", "frames", "frame_times", "edv_ml", "esv_ml",
           "ef_percent", "ed_frame", "es_frame", "wall_mass_g", "angles_40_80_pct_min", "min_angle_deg",
           "bad_triangles_per_frame", "conformity_mean_mm", "conformity_max_mm", "correspondence", "model_bytes",
           "seconds"]
SHOWN = [("subject", "subject"), ("structure", "structure"), ("exit_code", "exit"), ("edv_ml", "EDV ml"),
         ("esv_ml", "ESV ml"), ("ef_percent", "EF %"), ("wall_mass_g", "wall g"),
         ("angles_40_80_pct_min", "40–80° % (min)"), ("min_angle_deg", "min angle °"),
         ("conformity_max_mm", "conformity max mm"), ("seconds", "s")]


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def report_fields(s):
    """The table's fields from report.json's summary."""
    row = {k: s[k] for k in ("frames", "edv_ml", "esv_ml", "ef_percent", "ed_frame", "es_frame", "correspondence")}
    row["frame_times"] = s["frame_times_source"]
    if s.get("mass_g"):  # the myocardium: its mean mass over the frames
        row["wall_mass_g"] = round(sum(s["mass_g"]) / len(s["mass_g"]), 2)
    return row


def evaluation_fields(ev):
    """Quality and conformity from evaluation.json."""
    q = ev["summary"]
    row = {"angles_40_80_pct_min": round(min(f["quality"]["angles_40_80_pct"] for f in ev["frames"]), 2),
           "min_angle_deg": round(q["min_angle_deg"], 2), "bad_triangles_per_frame": q["bad_triangles_per_frame"]}
    if "conformity" in q:
        row["conformity_mean_mm"] = q["conformity"]["mean_of_frame_means_mm"]
        row["conformity_max_mm"] = q["conformity"]["max_mm"]
    return row


def row_of(unit):
    """One table row and the volume curve (times in ms or None, volumes in ml) of RESULTS/<subject>/<structure>."""
    subject, structure = os.path.normpath(unit).split(os.sep)[-2:]
    st = load(os.path.join(unit, "status.json")) or {"exit_code": 1, "message": "no status.json"}
    row = {"subject": subject, "structure": structure, "exit_code": st["exit_code"],
           "failed_step": st.get("failed_step", ""), "message": st.get("message", ""), "seconds": st.get("seconds")}
    report = load(os.path.join(unit, "mesh", "report.json"))
    ev = load(os.path.join(unit, "evaluation.json"))
    if row["exit_code"] != 0 or not report:
        return row, None
    s = report["summary"]
    row.update(report_fields(s))
    if ev:
        row.update(evaluation_fields(ev))
    if os.path.exists(os.path.join(unit, "model.c4d")):
        row["model_bytes"] = os.path.getsize(os.path.join(unit, "model.c4d"))
    times = s.get("frame_times_ms")
    times = times if times and None not in times else None
    return row, (times, s["volume_ml"])


def curve_png(curves):
    """One subject's volume curves {structure: (times or None, ml)} as a base64 PNG."""
    fig, ax = plt.subplots(figsize=(3.4, 2.1), dpi=100)
    timed = all(t is not None for t, _ in curves.values())
    for structure, (times, ml) in curves.items():
        ax.plot(times if timed else range(len(ml)), ml, marker="o", markersize=3, label=structure)
    ax.set_xlabel("time (ms)" if timed else "frame", fontsize=8)
    ax.set_ylabel("volume (ml)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    if list(curves) != ["default"]:  # name the structures, unless the input's only one
        ax.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode()


def fmt(v):
    return f"{v:.4g}" if isinstance(v, float) else html.escape(str(v if v is not None else ""))


def card(subject, rows, curves):
    lines = "".join(f"<p><b>{html.escape(r['structure'])}</b>: EDV {r['edv_ml']:.1f} ml · ESV {r['esv_ml']:.1f} ml · "
                    f"EF {r['ef_percent']:.1f} %" + (f" · wall {r['wall_mass_g']:.1f} g" if "wall_mass_g" in r else "")
                    + f" · {r['frames']} frame{'s' * (r['frames'] != 1)}</p>" for r in rows if r["exit_code"] == 0)
    return (f'<div class="card"><h3>{html.escape(subject)}</h3>'
            f'<img class="curve" alt="volume curve of {html.escape(subject)}" '
            f'src="data:image/png;base64,{curve_png(curves)}">{lines}</div>')


def table(rows, columns):
    head = "".join(f"<th>{html.escape(title)}</th>" for _, title in columns)
    body = "".join("<tr>" + "".join(f"<td>{fmt(r.get(k))}</td>" for k, _ in columns) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def write_html(path, rows, curves):
    subjects = list(dict.fromkeys(r["subject"] for r in rows))
    bad = [r for r in rows if r["exit_code"] != 0]
    cards = "".join(card(s, [r for r in rows if r["subject"] == s], curves[s]) for s in subjects if curves.get(s))
    failures = table(bad, [("subject", "subject"), ("structure", "structure"), ("failed_step", "step"),
                           ("exit_code", "exit code"), ("message", "message")]) if bad else "<p>none</p>"
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>contour4d cohort</title>
<style>body{{font-family:sans-serif;margin:20px}} .card{{display:inline-block;border:1px solid #ccc;margin:6px;
padding:6px;width:350px;vertical-align:top}} h3{{font-size:14px;margin:2px}} p{{font-size:12px;margin:2px}}
table{{border-collapse:collapse}} td,th{{border:1px solid #ccc;padding:3px 6px;font-size:12px}}</style></head>
<body><h1>contour4d cohort</h1>
<p>{len(subjects)} subjects, {len(rows)} subject-structures: {len(rows) - len(bad)} done, {len(bad)} failed.
The table is cohort.csv beside this page; each subject's files are in its folder.</p>
<h2>Failed</h2>{failures}
<h2>Volume curves</h2>{cards}
<h2>Table</h2>{table(rows, SHOWN)}
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
    rows, curves = [], {}
    for unit in a.units:
        row, curve = row_of(unit)
        rows.append(row)
        if curve:
            curves.setdefault(row["subject"], {})[row["structure"]] = curve
    with open(a.csv + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    os.replace(a.csv + ".tmp", a.csv)
    write_html(a.html, rows, curves)


if __name__ == "__main__":
    main()
