#!/usr/bin/python3
"""Corruption families of a biv-me GPFile folder, as clinical exports have them (issue: repair, don't refuse).

    corrupt_gpfile.py SRC DST FLAW [--frame F] [--slice S] [--seed N]

FLAW: open (a stretch of the contour removed: an open arc), loop (a small loop traced at one point),
spike (one point pulled 15 mm out), duplicate-slice (a re-acquired slice: a new slice id on the plane of
slice S, holding S's contour shifted 0.01 mm), one-point (a one-point contour on a new slice id),
backtrack (a stretch traced forward, back and forward again). The flaw goes into the SAX_LV_ENDOCARDIAL
contour of slice S (default: the first short-axis slice with one) in frame F. Two flaws touch every contour
of a slice: drop (slice S, default the middle one, left out of frame F and of about a third of the other
frames, chosen by the seed: contoured in some frames only) and shift (slice S, default the middle one, moved
2-5 mm in its plane in every frame, direction and size from the seed: a breath-hold shift). DST is a copy of
SRC with that change. Prints a JSON line saying what was done.
"""
import argparse, json, math, os, random, shutil, sys

TYPE = "SAX_LV_ENDOCARDIAL"


def read_rows(path):
    with open(path) as f:
        lines = f.read().splitlines()
    return lines[0], [l.split("\t") for l in lines[1:] if l.strip()]


def write_rows(path, header, rows):
    with open(path, "w") as f:
        f.write(header + "\n" + "\n".join("\t".join(r) for r in rows) + "\n")


def sax_ids(rows):
    return sorted({int(r[4]) for r in rows if r[3] == TYPE})


def in_plane_direction(rows, sid, rng):
    """A random unit vector in the plane of slice `sid` (its normal from Newell's formula on its contour)."""
    pts = [[float(x) for x in r[:3]] for r in rows if r[3] == TYPE and int(r[4]) == sid]
    nrm = [0.0, 0.0, 0.0]
    for i, p in enumerate(pts):
        q = pts[(i + 1) % len(pts)]
        nrm[0] += (p[1] - q[1]) * (p[2] + q[2])
        nrm[1] += (p[2] - q[2]) * (p[0] + q[0])
        nrm[2] += (p[0] - q[0]) * (p[1] + q[1])
    nl = math.sqrt(sum(x * x for x in nrm))
    nrm = [x / nl for x in nrm]
    e = [1.0, 0.0, 0.0] if abs(nrm[0]) < 0.9 else [0.0, 1.0, 0.0]
    u = [nrm[1] * e[2] - nrm[2] * e[1], nrm[2] * e[0] - nrm[0] * e[2], nrm[0] * e[1] - nrm[1] * e[0]]
    ul = math.sqrt(sum(x * x for x in u))
    u = [x / ul for x in u]
    v = [nrm[1] * u[2] - nrm[2] * u[1], nrm[2] * u[0] - nrm[0] * u[2], nrm[0] * u[1] - nrm[1] * u[0]]
    th = rng.uniform(0, 2 * math.pi)
    return [math.cos(th) * u[k] + math.sin(th) * v[k] for k in range(3)]


def whole_slice_flaw(a, rng, frames):
    """drop / shift: every contour of one slice id, in several frames (drop) or all of them (shift)."""
    _, rows0 = read_rows(os.path.join(a.dst, frames[a.frame]))
    ids = sax_ids(rows0)
    s = a.slice if a.slice is not None else ids[len(ids) // 2]
    what = {"flaw": a.flaw, "frame": a.frame, "slice": s}
    if a.flaw == "drop":
        others = [f for f in range(len(frames)) if f != a.frame]
        chosen = sorted([a.frame] + rng.sample(others, len(frames) // 3))
        what["frames"] = chosen
        targets = chosen
    else:
        size = rng.uniform(2.0, 5.0)
        d = [size * x for x in in_plane_direction(rows0, s, rng)]
        what["shift_mm"] = round(size, 3)
        targets = range(len(frames))
    for f in targets:
        path = os.path.join(a.dst, frames[f])
        header, rows = read_rows(path)
        if a.flaw == "drop":
            rows = [r for r in rows if not (r[3].startswith("SAX") and int(r[4]) == s)]
        else:
            for r in rows:
                if r[3].startswith("SAX") and int(r[4]) == s:
                    r[:3] = ["%.5f" % (float(r[k]) + d[k]) for k in range(3)]
        write_rows(path, header, rows)
    return what


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("src")
    p.add_argument("dst")
    p.add_argument("flaw", choices=["open", "loop", "spike", "duplicate-slice", "one-point", "backtrack", "drop", "shift"])
    p.add_argument("--frame", type=int, default=0)
    p.add_argument("--slice", type=int, default=None)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args()
    rng = random.Random(a.seed)
    if os.path.exists(a.dst):
        shutil.rmtree(a.dst)
    shutil.copytree(a.src, a.dst)
    frames = sorted(f for f in os.listdir(a.dst) if f.startswith("GPFile_") and f.endswith(".txt"))
    if a.flaw in ("drop", "shift"):
        print(json.dumps(whole_slice_flaw(a, rng, frames)))
        return 0
    path = os.path.join(a.dst, frames[a.frame])
    header, rows = read_rows(path)
    ids = sax_ids(rows)
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
    write_rows(path, header, rows)
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
