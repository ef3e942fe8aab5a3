#!/usr/bin/python3
"""Corruption families of a biv-me GPFile folder, as clinical exports have them (issue: repair, don't refuse).

    corrupt_gpfile.py SRC DST FLAW [--frame F] [--slice S] [--seed N]

FLAW: open (a stretch of the contour removed: an open arc), loop (a small loop traced at one point),
spike (one point pulled 15 mm out), duplicate-slice (a re-acquired slice: a new slice id on the plane of
slice S, holding S's contour shifted 0.01 mm), one-point (a one-point contour on a new slice id),
backtrack (a stretch traced forward, back and forward again). The flaw goes into the SAX_LV_ENDOCARDIAL
contour of slice S (default: the first short-axis slice with one) in frame F; DST is a copy of SRC with
that change. Prints a JSON line saying what was done.
"""
import argparse, json, math, os, random, shutil, sys

TYPE = "SAX_LV_ENDOCARDIAL"


def read_rows(path):
    with open(path) as f:
        lines = f.read().splitlines()
    return lines[0], [l.split("\t") for l in lines[1:] if l.strip()]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("src")
    p.add_argument("dst")
    p.add_argument("flaw", choices=["open", "loop", "spike", "duplicate-slice", "one-point", "backtrack"])
    p.add_argument("--frame", type=int, default=0)
    p.add_argument("--slice", type=int, default=None)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args()
    rng = random.Random(a.seed)
    if os.path.exists(a.dst):
        shutil.rmtree(a.dst)
    shutil.copytree(a.src, a.dst)
    frames = sorted(f for f in os.listdir(a.dst) if f.startswith("GPFile_") and f.endswith(".txt"))
    path = os.path.join(a.dst, frames[a.frame])
    header, rows = read_rows(path)
    ids = sorted({int(r[4]) for r in rows if r[3] == TYPE})
    s = a.slice if a.slice is not None else ids[0]
    idx = [k for k, r in enumerate(rows) if r[3] == TYPE and int(r[4]) == s]
    pts = [[float(x) for x in rows[k][:3]] for k in idx]
    n = len(pts)
    c = [sum(q[i] for q in pts) / n for i in range(3)]

    def row(q, sid=s):
        return ["%.5f" % q[0], "%.5f" % q[1], "%.5f" % q[2], TYPE, str(sid), "1.0", str(a.frame)]

    new_pts = list(pts)
    what = {"flaw": a.flaw, "frame": a.frame, "slice": s, "points": n}
    extra_rows, extra_info = [], None
    if a.flaw == "open":
        start, length = rng.randrange(n), max(3, int(0.3 * n))
        keep = [(start + length + k) % n for k in range(n - length)]
        new_pts = [pts[k] for k in keep]
        what["removed"] = length
    elif a.flaw in ("loop", "spike", "backtrack"):
        i = rng.randrange(n)
        p0, p1 = pts[i], pts[(i + 1) % n]
        t = [p1[k] - p0[k] for k in range(3)]
        tl = math.sqrt(sum(x * x for x in t)) or 1.0
        t = [x / tl for x in t]
        out = [p0[k] - c[k] for k in range(3)]
        ol = math.sqrt(sum(x * x for x in out)) or 1.0
        out = [x / ol for x in out]
        if a.flaw == "spike":
            ins = [[p0[k] + 15.0 * out[k] for k in range(3)]]
        elif a.flaw == "loop":  # a 3 mm loop that crosses the contour: forward, out, back across, in
            r = 1.5
            ins = [[p0[k] + r * (math.cos(th) * t[k] + math.sin(th) * out[k]) + r * t[k] for k in range(3)]
                   for th in [math.pi + 2 * math.pi * j / 8 for j in range(1, 8)]]
        else:  # backtrack over the next 3 points and forward again
            j = [(i + m) % n for m in range(1, 4)]
            ins = [pts[j[0]], pts[j[1]], pts[j[2]], pts[j[1]], pts[j[0]]]
            ins = [[q[k] + 0.05 * out[k] for k in range(3)] for q in ins]
        new_pts = pts[: i + 1] + ins + pts[i + 1:]
        what["at"] = i
    elif a.flaw == "duplicate-slice":
        sid = max(int(r[4]) for r in rows) + 50
        extra_rows = [row([q[0] + 0.01, q[1], q[2]], sid) for q in pts]
        extra_info = (s, sid)
        what["new_slice"] = sid
    elif a.flaw == "one-point":
        sid = max(int(r[4]) for r in rows) + 60
        extra_rows = [row(c, sid)]
        extra_info = (s, sid)
        what["new_slice"] = sid
    first, last = idx[0], idx[-1]
    rows = rows[:first] + [row(q) for q in new_pts] + rows[last + 1:] + extra_rows
    with open(path, "w") as f:
        f.write(header + "\n" + "\n".join("\t".join(r) for r in rows) + "\n")
    if extra_info:  # the new slice id gets the plane of the old one in SliceInfoFile.txt
        info = os.path.join(a.dst, "SliceInfoFile.txt")
        with open(info) as f:
            lines = f.read().splitlines()
        for l in lines:
            parts = l.split("\t")
            if len(parts) > 2 and parts[1].startswith("sliceID") and int(parts[2]) == extra_info[0]:
                parts = list(parts)
                parts[0] = "reacquired-" + parts[0]
                parts[2] = str(extra_info[1])
                lines.append("\t".join(parts))
                break
        with open(info, "w") as f:
            f.write("\n".join(lines) + "\n")
    print(json.dumps(what))


if __name__ == "__main__":
    sys.exit(main())
