#!/usr/bin/env python3
"""Forced gaps of a run's state, independent of the contact elements (docs/SCENE.md "Forced
normals"): for every pair of fibres of different classes whose levels differ, the closest points
of their two centrelines (sampled at --samples points per quadratic element, brute force), the
fibre with the higher level there on top, and the gap along the forced direction D that the
forced law would give at those points:

    g = (x_top - x_bottom) . D - (R_top + R_bottom) + A

(mm, A the allowance left at the state's time, R the reference radii: the solver's half-widths
of the deformed sections differ by the sections' strain, 1.7e-5 mm on samples/forced_normals.json
after its forced step). Prints the deepest gaps (most negative first)
with the centrelines' distance d there, and counts the pairs with g < 0 whose d exceeds --reach
(the proximity distance): pairs that the forced law would push apart but that detection, which
looks only within Δprox, does not see.

  fibra expand bench/woven_thick_7.json --out /tmp/thick.json
  python3 bench/forced_gaps.py OUT/final_state.csv /tmp/thick.json --allowance 0.0890 \\
      --reach 0.078
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from centreline_overlap import load_fibres, samples  # noqa: E402


def fail(msg):
    sys.exit("forced_gaps.py: " + msg)


def level_at(levels, s):
    if not isinstance(levels, list):
        return float(levels)
    value = levels[0][1]
    for start, lv in levels:
        if s >= start:
            value = lv
    return float(value)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("state", help="final_state.csv of a run")
    ap.add_argument("scene", help="the scene expanded to plain JSON (fibra expand)")
    ap.add_argument("--allowance", type=float, default=0.0, help="A left at the state, mm")
    ap.add_argument("--direction", default="0,0,1", help="forced direction D, x,y,z")
    ap.add_argument("--reach", type=float, required=True, help="proximity distance, mm")
    ap.add_argument("--samples", type=int, default=8, help="points per element")
    ap.add_argument("--show", type=int, default=8, help="pairs printed")
    a = ap.parse_args()
    try:
        d = [float(v) for v in a.direction.split(",")]
    except ValueError:
        d = []
    if len(d) != 3 or not all(math.isfinite(v) for v in d) or not any(d):
        fail(f"--direction: three finite numbers x,y,z, not all zero (got '{a.direction}')")
    norm = math.hypot(*d)
    d = [v / norm for v in d]
    if not a.reach > 0 or not math.isfinite(a.reach):
        fail(f"--reach: a proximity distance > 0, mm (got {a.reach})")
    if a.samples < 1:
        fail(f"--samples: at least 1 point per element (got {a.samples})")
    if not a.allowance >= 0 or not math.isfinite(a.allowance):
        fail(f"--allowance: a finite overlap >= 0, mm (got {a.allowance})")
    try:
        fibres = {f["name"]: f for f in json.load(open(a.scene))["fibres"]}
        for f in fibres.values():
            float(f["radius"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"{a.scene}: not an expanded scene whose fibres have names and radii ({e}; "
             "write one with `fibra expand SCENE --out FILE`)")
    state = load_fibres(a.state)
    if not set(state) & set(fibres):
        fail(f"{a.state} and {a.scene}: no fibre name in common (the state of another scene?)")
    # (centre, fraction of the arc length) at the samples of each fibre
    pts = {}
    for name, rows in state.items():
        elements = (len(rows) - 1) // 2
        pts[name] = [(x0, u / elements) for u, x0, _, _ in samples(rows, a.samples)]
    names = sorted(n for n in pts if n in fibres)
    pairs = []
    for i, ni in enumerate(names):
        for nj in names[i + 1:]:
            fi, fj = fibres[ni], fibres[nj]
            if fi.get("class", "") == fj.get("class", ""):
                continue
            best = (math.inf, None, None)
            for pi, si in pts[ni]:
                for pj, sj in pts[nj]:
                    dd = sum((pi[q] - pj[q]) ** 2 for q in range(3))
                    if dd < best[0]:
                        best = (dd, (pi, si), (pj, sj))
            (pi, si), (pj, sj) = best[1], best[2]
            li = level_at(fi.get("levels", 0), si * fi_length(fi))
            lj = level_at(fj.get("levels", 0), sj * fi_length(fj))
            if li == lj:
                continue
            top, bottom = (pi, pj) if li > lj else (pj, pi)
            along = sum((top[q] - bottom[q]) * d[q] for q in range(3))
            gap = along - fi["radius"] - fj["radius"] + a.allowance
            pairs.append((gap, math.sqrt(best[0]), ni, si, nj, sj))
    pairs.sort()
    unseen = [p for p in pairs if p[0] < 0 and p[1] > a.reach]
    print(f"{len(pairs)} forced pairs, {sum(p[0] < 0 for p in pairs)} with a negative gap, "
          f"{len(unseen)} of them beyond the reach {a.reach} mm")
    for gap, dist, ni, si, nj, sj in pairs[:a.show]:
        print(f"  gap {gap:.6f} mm  d {dist:.5f} mm  {ni} at {si:.3f} L, {nj} at {sj:.3f} L"
              + ("  beyond the reach" if dist > a.reach else ""))


def fi_length(f):
    """Reference arc length of a fibre of line geometry (the generators' fibres; a polyline of
    several points sums its pieces), mm."""
    g = f.get("geometry", {})
    if g.get("type") != "line":
        fail(f"fibre '{f['name']}': only line geometries are read (levels are by arc length)")
    points = g.get("points", [])
    return sum(math.dist(p, q) for p, q in zip(points, points[1:]))


if __name__ == "__main__":
    main()
