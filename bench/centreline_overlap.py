#!/usr/bin/env python3
"""Brute-force true overlap of a run's fibres, from its final_state.csv (independent of the
contact elements): every fibre's centreline and directors sampled at --samples points per
element (quadratic elements: Lagrange interpolation of the three nodes), every pair of samples
on different fibres, or on one fibre more than --min-elements elements apart (self-contact),
within --reach mm; the overlap of a pair is w_a + w_b - d with d the distance of the two points
and w = R |G^T n| each fibre's half-width along n = the direction between them (G = [g1 g2]).
Prints the largest overlap (mm and in units of --pmax) and where it is.

  python3 bench/centreline_overlap.py out/plectoneme/final_state.csv --radius 0.1 \
      --pmax 5e-4 --min-elements 4
"""
import argparse
import csv
import math
from collections import defaultdict


def samples(rows, per_element):
    """[(element, x0, g1, g2)] along one fibre of quadratic elements."""
    out = []
    elements = (len(rows) - 1) // 2
    for e in range(elements):
        for k in range(per_element + (e == elements - 1)):
            z = -1 + 2 * k / per_element
            N = (z * (z - 1) / 2, 1 - z * z, z * (z + 1) / 2)
            v = [sum(N[a] * rows[2 * e + a][c] for a in range(3)) for c in range(9)]
            out.append((e + (z + 1) / 2, v[0:3], v[3:6], v[6:9]))
    return out


def half_width(g1, g2, n, radius):
    dot = lambda a, b: sum(x * y for x, y in zip(a, b))
    return radius * math.hypot(dot(g1, n), dot(g2, n))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("final_state")
    p.add_argument("--radius", type=float, required=True, help="fibre radius R, mm")
    p.add_argument("--pmax", type=float, default=0, help="p_max, mm (for the ratio)")
    p.add_argument("--samples", type=int, default=16, help="samples per element")
    p.add_argument("--min-elements", type=float, default=4,
                   help="self-contact: pairs on one fibre at least this many elements apart")
    p.add_argument("--reach", type=float, default=0, help="pairs within this distance, mm (0: 2.5 R)")
    a = p.parse_args()
    fibres = defaultdict(list)
    for r in csv.DictReader(open(a.final_state)):
        fibres[r["fibre"]].append([float(r[k]) for k in
                                   ("x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z")])
    pts = [(f, s) for f, rows in fibres.items() for s in samples(rows, a.samples)]
    reach = a.reach or 2.5 * a.radius
    best = (0.0, None, None)
    for i in range(len(pts)):
        fi, (ei, xi, g1i, g2i) = pts[i]
        for j in range(i + 1, len(pts)):
            fj, (ej, xj, g1j, g2j) = pts[j]
            if fi == fj and abs(ei - ej) < a.min_elements:
                continue
            d = math.dist(xi, xj)
            if d == 0 or d > reach:
                continue
            n = [(u - v) / d for u, v in zip(xi, xj)]
            overlap = half_width(g1i, g2i, n, a.radius) + half_width(g1j, g2j, n, a.radius) - d
            if overlap > best[0]:
                best = (overlap, (fi, ei, xi), (fj, ej, xj))
    overlap, A, B = best
    ratio = f" ({overlap / a.pmax:.2f} p_max)" if a.pmax > 0 else ""
    print(f"largest overlap {overlap:.4g} mm{ratio}")
    if A:
        for f, e, x in (A, B):
            print(f"  fibre {f}, element coordinate {e:.3f}, at ({x[0]:.4f}, {x[1]:.4f}, {x[2]:.4f})")


if __name__ == "__main__":
    main()
