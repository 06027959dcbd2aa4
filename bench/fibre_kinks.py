#!/usr/bin/env python3
"""Kinks of a run's fibres at their element ends, from its final_state.csv: at every interior
element end of every fibre (of quadratic elements, fibra's default), the angle between the tangents of the two
elements that meet there (dx/dz of each element's Lagrange interpolation of its three nodes, at
z = +1 and z = -1). A fibre with bending stiffness is smooth there to discretisation error; a
string (bending_factor 0) may zigzag from node to node. Prints the mean and the largest angle
(degrees) and where the largest is.

  python3 bench/fibre_kinks.py out/yarn_procedure/final_state.csv
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from centreline_overlap import load_fibres  # noqa: E402


def tangent_end(a, b, c):
    """dx/dz at z = +1 of the element with nodes a, b, c (z = -1, 0, 1)."""
    return [0.5 * p - 2 * q + 1.5 * r for p, q, r in zip(a, b, c)]


def tangent_start(a, b, c):
    """dx/dz at z = -1 of the element with nodes a, b, c."""
    return [-1.5 * p + 2 * q - 0.5 * r for p, q, r in zip(a, b, c)]


def angle(u, v):
    dot = sum(x * y for x, y in zip(u, v))
    return math.degrees(math.acos(max(-1.0, min(1.0, dot / math.hypot(*u) / math.hypot(*v)))))


def fibre_kinks(rows):
    """(angle in degrees, node) at every interior element end of one fibre's node rows."""
    out = []
    for e in range(1, (len(rows) - 1) // 2):  # the end shared by elements e - 1 and e: node 2 e
        left = tangent_end(*rows[2 * e - 2:2 * e + 1])
        right = tangent_start(*rows[2 * e:2 * e + 3])
        out.append((angle(left, right), 2 * e))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("final_state")
    a = p.parse_args()
    fibres = load_fibres(a.final_state, ("x", "y", "z"))
    kinks = [(k, name, node) for name, rows in fibres.items() for k, node in fibre_kinks(rows)]
    if not kinks:
        print("no interior element ends")
        return
    worst = max(kinks)
    mean = sum(k[0] for k in kinks) / len(kinks)
    print(f"{len(kinks)} interior element ends: mean kink {mean:.2f} deg, largest {worst[0]:.2f} deg "
          f"(fibre {worst[1]}, node {worst[2]})")


if __name__ == "__main__":
    main()
