#!/usr/bin/env python3
"""A fibre under tension, its end section turned about its own axis: straight or buckled?

Greenhill's criterion (Love, "A treatise on the mathematical theory of elasticity", §272): a rod of
bending stiffness B under tension T and an axial torque M stays straight while M < 2 sqrt(B T)
(long rod; finite length raises the limit a little). With bending_factor 0 only the tension's
geometric stiffness T R^2 / 4 is left, the limit is T R, and beyond it the string zigzags from
node to node (docs/METHOD.md "Strings under torque").

For every combination of the given bending factors, torsion factors and element counts, the script
writes the scene of tests/test_twisted_string.cpp (the glass fibre of samples/yarn_procedure.json:
R = 0.01 mm, E = 73 000 MPa, nu = 0.3, L = 0.5 mm, T = 0.023 N, the end turned by --turn rad, a
transverse line load --imperfection N/mm along x; --tension and --radius change T and R), runs
`fibra run`, and prints the torque M = torsion_factor G J phi / L, M over Greenhill's
2 sqrt(B T), the largest deflection out of the load's plane (|y|) and the largest kink between
two elements at a shared end (for a run that fails, of its last converged state).

    python3 bench/twisted_string.py --fibra build/fibra --bending 0.01,0.03,0.07 --elements 16,32
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from centreline_overlap import load_fibres  # noqa: E402
from fibre_kinks import fibre_kinks  # noqa: E402

E, NU, R, L, T = 73000.0, 0.3, 0.01, 0.5, 0.023  # MPa, -, mm, mm, N


def scene(bending, torsion, elements, turn, imperfection, tension, radius):
    return {
        "units": "mm-N-MPa",
        "materials": [{"name": "glass", "young_modulus": E, "poisson_ratio": NU,
                       "bending_factor": bending, "torsion_factor": torsion}],
        "fibres": [{"name": "s", "material": "glass", "radius": radius, "elements": elements,
                    "order": 2, "geometry": {"type": "line", "points": [[0, 0, 0], [0, 0, L]],
                                             "director": [1, 0, 0]}}],
        "tables": {"pull": [[0, 0], [1, 1], [2, 1]], "turn": [[0, 0], [1, 0], [2, turn]]},
        "boundary_conditions": [
            {"type": "fix", "group": "s.start", "dofs": ["x", "y", "z", "g1", "g2"]},
            {"type": "fix", "group": "s.end", "dofs": ["x", "y", "g1", "g2"],
             "rotation": {"axis": [0, 0, 1], "centre": [0, 0, 0], "angle": "turn"}}],
        "loads": [{"type": "force", "group": "s.end", "vector": [0, 0, tension], "table": "pull"},
                  {"type": "line_force", "group": "s.all", "vector": [imperfection, 0, 0],
                   "table": "pull"}],
        "stabilisation": {"stiffness": 1e-3},
        "steps": [{"name": "pull", "end_time": 1, "increments": 2},
                  {"name": "turn", "end_time": 2, "increments": 10}]}


def shape(state):
    """Largest |y| (mm) and largest kink (deg) of the fibre in a final_state.csv."""
    rows = next(iter(load_fibres(state, ("x", "y", "z")).values()))
    kinks = [k for k, _ in fibre_kinks(rows)]
    return max(abs(p[1]) for p in rows), max(kinks, default=0.0)


def numbers(text, kind, name):
    try:
        values = [kind(v) for v in text.split(",")]
    except ValueError:
        what = "whole numbers" if kind is int else "numbers"
        sys.exit(f"twisted_string.py: --{name}: expected {what} separated by commas, got '{text}'")
    if any(not math.isfinite(v) or v < 0 or (kind is int and v < 1) for v in values):
        sys.exit(f"twisted_string.py: --{name}: expected finite values >= 0 (elements >= 1), "
                 f"got '{text}'")
    return values


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--fibra", default="build/fibra")
    p.add_argument("--bending", default="0.01,0.07", help="bending factors, comma-separated")
    p.add_argument("--torsion", default="1", help="torsion factors, comma-separated")
    p.add_argument("--elements", default="16", help="elements per fibre, comma-separated")
    p.add_argument("--turn", type=float, default=math.pi / 2, help="end turn, rad")
    p.add_argument("--imperfection", type=float, default=1e-4, help="line load, N/mm")
    p.add_argument("--tension", type=float, default=T, help="end force along the fibre, N")
    p.add_argument("--radius", type=float, default=R, help="fibre radius, mm")
    a = p.parse_args()
    for name in ("turn", "imperfection", "tension", "radius"):
        value = getattr(a, name)
        if not math.isfinite(value) or (name in ("tension", "radius") and value <= 0):
            sys.exit(f"twisted_string.py: --{name}: expected a finite value"
                     f"{' > 0' if name in ('tension', 'radius') else ''}, got {value}")
    if not os.access(a.fibra, os.X_OK):
        sys.exit(f"twisted_string.py: --fibra: {a.fibra} is not an executable (build fibra first)")
    G, J, I = E / (2 * (1 + NU)), math.pi * a.radius ** 4 / 2, math.pi * a.radius ** 4 / 4
    bendings = numbers(a.bending, float, "bending")
    torsions = numbers(a.torsion, float, "torsion")
    counts = numbers(a.elements, int, "elements")
    print("bending torsion elements | M N mm | M / 2 sqrt(B T) | solved | |y| max mm | kink max deg"
          " (unsolved: the last converged state)")
    with tempfile.TemporaryDirectory() as tmp:
        for bf in bendings:
            for tf in torsions:
                for n in counts:
                    path = os.path.join(tmp, "s.json")
                    with open(path, "w") as f:
                        json.dump(scene(bf, tf, n, a.turn, a.imperfection, a.tension, a.radius), f)
                    out = os.path.join(tmp, "out")
                    run = subprocess.run([a.fibra, "run", path, "--out", out, "--quiet",
                                          "--threads", "1"], capture_output=True, text=True)
                    solved = "solved" in run.stdout + run.stderr
                    state = os.path.join(out, "final_state.csv")
                    if not os.path.exists(state):
                        sys.exit(f"twisted_string.py: fibra wrote no state for bending {bf:g}, "
                                 f"torsion {tf:g}, {n} elements (exit {run.returncode}): "
                                 f"{(run.stderr or run.stdout).strip()}")
                    y, kink = shape(state)
                    M = tf * G * J * a.turn / L
                    ratio = M / (2 * math.sqrt(bf * E * I * a.tension)) if bf > 0 else math.inf
                    print(f"{bf:g} {tf:g} {n} | {M:.3g} | {ratio:.2f} | "
                          f"{'yes' if solved else 'no'} | {y:.2e} | {kink:.2f}", flush=True)


if __name__ == "__main__":
    main()
