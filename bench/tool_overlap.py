#!/usr/bin/env python3
"""Brute-force true overlap of a run's fibres with rigid cylinders, from its final_state.csv
(independent of the tool contact elements): every fibre's centreline and directors sampled at
--samples points per element (fibres of quadratic elements, fibra's default: Lagrange
interpolation of the three nodes),
each sample's overlap with each cylinder rho + w - d (outside the cylinder) with d the distance
of the centreline point from the cylinder's axis and w = R |G^T n| the fibre's half-width along
n = the direction from the axis (G = [g1 g2]). The cylinders are given where they are at the
final state (point of the axis after the tool's displacement, axis, radius), with the fibres
outside them (a cylinder with the fibres inside is not measured). Prints the largest
overlap (mm and in units of --pmax) and where it is.

  python3 bench/tool_overlap.py out/yarn_procedure/final_state.csv --radius 0.01 --pmax 1e-4 \\
      --cylinder 0,-0.138,0.25,1,0,0,0.1 --cylinder 0,0.138,0.25,1,0,0,0.1
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from centreline_overlap import half_width, load_fibres, section, state_parser  # noqa: E402


def cylinder(text):
    v = [float(x) for x in text.split(",")]
    if len(v) != 7 or not all(math.isfinite(x) for x in v) or not v[6] > 0:
        raise argparse.ArgumentTypeError("expected px,py,pz,ax,ay,az,radius with radius > 0")
    a = math.sqrt(sum(x * x for x in v[3:6]))
    if a == 0:
        raise argparse.ArgumentTypeError("the axis is zero")
    return v[0:3], [x / a for x in v[3:6]], v[6]


def main():
    p = state_parser(__doc__, 400)
    p.add_argument("--cylinder", type=cylinder, action="append", required=True,
                   help="px,py,pz,ax,ay,az,radius at the final state (repeatable)")
    a = p.parse_args()
    if a.samples < 1 or not a.radius > 0 or not a.pmax >= 0:
        p.error("--samples must be >= 1, --radius > 0 and --pmax >= 0")
    fibres = load_fibres(a.final_state)
    best = (0.0, None, None, None)
    for name, rows in fibres.items():
        elements = (len(rows) - 1) // 2
        for k in range(elements * a.samples + 1):
            u = k / a.samples
            x, g1, g2 = section(rows, u)
            for c, (point, axis, rho) in enumerate(a.cylinder):
                d = [x[i] - point[i] for i in range(3)]
                along = sum(d[i] * axis[i] for i in range(3))
                radial = [d[i] - along * axis[i] for i in range(3)]
                dist = math.sqrt(sum(v * v for v in radial))
                if dist == 0:
                    continue
                n = [v / dist for v in radial]
                overlap = rho + half_width(g1, g2, n, a.radius) - dist
                if overlap > best[0]:
                    best = (overlap, name, u, c)
    overlap, name, u, c = best
    if name is None:
        print("no overlap with the cylinders")
        return
    ratio = f" ({overlap / a.pmax:.2f} p_max)" if a.pmax > 0 else ""
    print(f"largest overlap {overlap:.4g} mm{ratio}: fibre {name}, element coordinate {u:.3f}, "
          f"cylinder {c}")


if __name__ == "__main__":
    main()
