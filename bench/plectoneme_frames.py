#!/usr/bin/env python3
"""Frame-by-frame measures of a plectoneme run written with --vtu-format ascii and
"output_every": 1 (bench/plectoneme.json): per frame the active self-contact elements and the
elements' largest reported penetration (history.csv), the loop's smallest centreline distance
(points more than 4 elements apart and more than 0.8 element from either end, 8 samples per
element) and the brute-force overlap (bench/centreline_overlap.py on the frame's nodes and
directors, the end discs included). A frame is
"formed" when self-contact is active and that distance is within 2R + p_max. Prints a row
every --every frames and the formed count.

  build/fibra run bench/plectoneme.json --out out/plectoneme --vtu-format ascii
  python3 bench/plectoneme_frames.py out/plectoneme --radius 0.1 --pmax 5e-4
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

from centreline_overlap import section


def frame_nodes(path):
    """[[x, y, z, g1..., g2...] per node] of the first fibre's polyline in an ascii frame."""
    try:
        text = open(path, "rb").read().decode("ascii", errors="replace")
    except OSError as e:
        raise SystemExit(f"{path}: {e.strerror}")

    def block(name):
        m = re.search(r'Name="%s"[^>]*format="ascii"[^>]*>(.*?)</DataArray>' % name, text, re.S)
        if not m:
            raise SystemExit(f"{path}: no ascii array {name} (run with --vtu-format ascii)")
        return m.group(1).split()

    if len(set(block("fibre"))) > 1:
        raise SystemExit(f"{path}: several fibres; this script measures a single rod")
    n = int(block("offsets")[0])
    points = re.search(r"<Points>.*?>(.*?)</DataArray>", text, re.S).group(1).split()
    p, g1, g2 = (list(map(float, a)) for a in (points, block("g1"), block("g2")))
    return [p[3 * i:3 * i + 3] + g1[3 * i:3 * i + 3] + g2[3 * i:3 * i + 3] for i in range(n)]


def smallest_distance(rows):
    elements = (len(rows) - 1) // 2
    pts = [(u / 8, section(rows, u / 8)[0]) for u in range(elements * 8 + 1)]
    pts = [p for p in pts if 0.8 <= p[0] <= elements - 0.8]
    return min((math.dist(a[1], b[1]) for i, a in enumerate(pts) for b in pts[i + 1:]
                if b[0] - a[0] > 4), default=math.inf)


def overlap(rows, radius, pmax):
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write("fibre,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n")
        for r in rows:
            f.write("rod," + ",".join("%.17g" % v for v in r) + "\n")
    here = os.path.dirname(os.path.abspath(__file__))
    out = subprocess.run([sys.executable, os.path.join(here, "centreline_overlap.py"), f.name,
                          "--radius", str(radius), "--pmax", str(pmax), "--samples", "8"],
                         capture_output=True, text=True)
    os.unlink(f.name)
    m = re.search(r"\(([0-9.]+) p_max\)", out.stdout)
    return float(m.group(1)) if m else math.nan


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run")
    p.add_argument("--radius", type=float, required=True)
    p.add_argument("--pmax", type=float, required=True)
    p.add_argument("--every", type=int, default=10, help="print every n-th frame")
    a = p.parse_args()
    try:
        history = list(csv.DictReader(open(os.path.join(a.run, "history.csv"))))
    except OSError as e:
        raise SystemExit(f"{a.run}/history.csv: {e.strerror}")
    frames = len([f for f in os.listdir(a.run) if re.fullmatch(r"result_\d{4}\.vtu", f)])
    # A frame per history row and the start's; a run that failed writes one more, its last
    # converged sub-increment, which has no row and is not measured.
    if frames not in (len(history) + 1, len(history) + 2):
        raise SystemExit(f"{a.run}: {frames} frames for {len(history)} history rows; this script "
                         "needs a frame per increment (\"output_every\": 1, the bench scene's)")
    formed = []
    print("t, active, reported p_max, smallest centreline distance mm, brute-force p_max, viscous")
    for k, h in enumerate(history, start=1):
        rows = frame_nodes(os.path.join(a.run, f"result_{k:04d}.vtu"))
        d, active = smallest_distance(rows), int(h["contact.active"])
        if active > 0 and d <= 2 * a.radius + a.pmax:
            formed.append(float(h["time"]))
        if k % a.every == 0:
            print(f"{float(h['time']):.3f}, {active}, {float(h['contact.max_penetration_ratio']):.2f}, "
                  f"{d:.3f}, {overlap(rows, a.radius, a.pmax):.2f}, {float(h.get('viscous_force') or 0):.3f}")
    span = f" (t = {formed[0]:.3f} to {formed[-1]:.3f})" if formed else ""
    print(f"formed in {len(formed)} of {len(history)} frames{span}")


if __name__ == "__main__":
    main()
