#!/usr/bin/env python3
"""Writes the reduced woven-fabric test scenes samples/fabric_biaxial.json and
samples/fabric_shear.json (docs/SCENE.md "Fabric test loadings").

fibra's boundary conditions hold a DOF for the whole run, so a fibre end cannot slide under a
small tension during the initial geometry and then be driven. The scenes therefore hold every
fibre's start at the x (warp) or y (weft) it reaches in the force-controlled initial geometry
(the yarns' crimp pulls the free starts inward), read from that run's final_state.csv:

  python3 scripts/fabric_loadings.py --settle            # writes /tmp/fabric_settle.json
  fibra run /tmp/fabric_settle.json --out /tmp/fabric_settle --threads 1
  python3 scripts/fabric_loadings.py --from /tmp/fabric_settle/final_state.csv

Units: mm, N, MPa.
"""
import argparse
import csv
import json

ELEMENTS = 12          # quadratic elements per fibre (nodes 0 .. 2 ELEMENTS)
TENSION = 0.01         # N per fibre end, the small tension of the initial geometry
MU = 0.1               # friction between yarns in the loading scenes
STRAIN = 0.004         # biaxial: elongation / length at the end of the test
SHEAR_U = 0.05         # shear: edge displacement amplitude, mm (+-, each edge)
CYCLES = 2             # shear cycles
QUARTER = 2            # shear increments per quarter cycle
DAMPING = 0.1          # shear: viscous continuation, N/mm x pseudo-time per node


def fabric():
    yarn = {"yarns": 2, "spacing": 1.5, "fibres_per_yarn": 3, "fibre_radius": 0.1,
            "gap": 0.01, "material": "polymer", "elements": ELEMENTS}
    return {"type": "woven_fabric", "name": "fab", "pattern": "plain",
            "warp": dict(yarn), "weft": dict(yarn)}


def base(description):
    return {
        "description": description,
        "units": "mm-N-MPa",
        "materials": [{"name": "polymer", "young_modulus": 4000, "poisson_ratio": 0.3}],
        "generators": [fabric()],
        "contact": {"max_penetration": 5e-4, "friction": 0, "max_reversible_slip": 5e-4,
                    "pairs": [{"classes": "within", "max_penetration": 1e-3}]},
    }


def fibres():
    return [f"fab.{d}{y}.f{k}" for d in ("warp", "weft") for y in range(2) for k in range(3)]


def settle_scene():
    """Force control: the ends (xmax, ymax) held, the starts free along their yarn under the
    small tension; forced normals, then the normal rules."""
    s = base("initial geometry under end tensions (to measure the starts' crimp contraction)")
    s["boundary_conditions"] = [
        {"type": "fix", "group": "fab.warp.end", "dofs": ["x0", "g1y"]},
        {"type": "fix", "group": "fab.weft.end", "dofs": ["x0", "g1x"]},
        {"type": "fix", "group": "fab.warp.start", "dofs": ["y", "z"]},
        {"type": "fix", "group": "fab.weft.start", "dofs": ["x", "z"]}]
    s["loads"] = [
        {"type": "force", "group": "fab.warp.start", "vector": [-TENSION, 0, 0], "table": "one"},
        {"type": "force", "group": "fab.weft.start", "vector": [0, -TENSION, 0], "table": "one"}]
    s["tables"] = {"one": [[0, 1], [1, 1]]}
    s["steps"] = initial_steps()
    s["output"] = {"vtu": False}
    return s


def initial_steps():
    """Forced normals, then the normal rules, both frictionless (friction_factor 0: friction
    breaks the forced step); the loading steps that follow have the scene's friction."""
    return [{"name": "initial_geometry", "end_time": 1, "increments": 4,
             "forced_normals": {"direction": [0, 0, 1]}, "friction_factor": 0},
            {"name": "normal_rules", "end_time": 2, "increments": 1, "friction_factor": 0}]


def start_shifts(final_state):
    """Each fibre's start displacement along its yarn (mm) at the end of the settle run."""
    out = {}
    with open(final_state) as f:
        for row in csv.DictReader(f):
            if row["node"] != "0":
                continue
            warp = ".warp" in row["fibre"]
            out[row["fibre"]] = float(row["x"]) + 2.25 if warp else float(row["y"]) + 2.25
    return out


def held_starts(shifts, table_of):
    """Per fibre: the start held along the yarn (its crimp shift, then the test's motion) and
    across it in z; the other in-plane DOF is left to the caller."""
    bcs = []
    for f in fibres():
        warp = ".warp" in f
        bcs.append({"type": "fix", "group": f + ".start", "dofs": ["x" if warp else "y", "z"],
                    "displacement": [1, 0, 0] if warp else [0, 1, 0],
                    "table": table_of(shifts[f])})
    return bcs


def biaxial(shifts):
    s = base("2 x 2 plain weave, 3 fibres per yarn: initial geometry, then biaxial tension "
             "(equal elongation in warp and weft, 20 increments)")
    s["contact"]["pairs"].append({"classes": ["fab.warp", "fab.weft"], "friction": MU})
    L = 4.5
    stretch = lambda c: [[0, 0], [0.25, c], [2, c], [3, c - STRAIN * L]]
    s["boundary_conditions"] = [
        {"type": "fix", "group": "fab.warp.end", "dofs": ["x0", "g1y"]},
        {"type": "fix", "group": "fab.weft.end", "dofs": ["x0", "g1x"]},
        {"type": "fix", "group": "fab.warp.start", "dofs": ["y"]},
        {"type": "fix", "group": "fab.weft.start", "dofs": ["x"]}] + held_starts(shifts, stretch)
    s["steps"] = initial_steps() + [{"name": "biaxial_tension", "end_time": 3,
                                     "increments": 20}]
    s["output"] = {"vtu": False, "probes": [{"name": "warp_start", "fibre": "fab.warp0.f0",
                                             "node": 0}],
                   "plots": [{"x": "probe.warp_start.x",
                              "y": ["reaction.fab.warp.end.fx", "reaction.fab.weft.end.fy"],
                              "file": "biaxial_force.png",
                              "title": "biaxial tension: edge force (N) vs warp start x (mm)"}]}
    return s


def shear(shifts):
    s = base("2 x 2 plain weave, 3 fibres per yarn: initial geometry, then cyclic shear "
             "(the warp yarns' ends moved in opposite directions along y, alternately)")
    s["contact"]["pairs"].append({"classes": ["fab.warp", "fab.weft"], "friction": MU})
    hold = lambda c: [[0, 0], [0.25, c]]
    cycle = [[2, 0]]
    for k in range(CYCLES):
        t = 2 + 4 * k
        cycle += [[t + 1, SHEAR_U], [t + 3, -SHEAR_U]]
    cycle.append([2 + 4 * CYCLES, 0])
    s["tables"] = {"cycle": cycle}
    s["boundary_conditions"] = [
        {"type": "fix", "group": "fab.warp.end", "dofs": ["x0", "g1y"],
         "displacement": [0, -1, 0], "table": "cycle"},
        {"type": "fix", "group": "fab.weft.end", "dofs": ["x0", "g1x"]},
        {"type": "fix", "group": "fab.warp.start", "dofs": ["y"],
         "displacement": [0, 1, 0], "table": "cycle"},
        {"type": "fix", "group": "fab.weft.start", "dofs": ["x"]}] + held_starts(shifts, hold)
    steps = initial_steps()
    t = 2
    quarters = [(1, QUARTER)] + [(2, 2 * QUARTER)] * (2 * CYCLES - 1) + [(1, QUARTER)]
    for k, (dt, n) in enumerate(quarters):
        t += dt
        steps.append({"name": f"shear_{k}", "end_time": t, "increments": n, "damping": DAMPING})
    s["steps"] = steps
    s["output"] = {"vtu": False, "probes": [{"name": "warp_start", "fibre": "fab.warp0.f0",
                                             "node": 0}],
                   "plots": [{"x": "probe.warp_start.y", "y": "reaction.fab.warp.end.fy",
                              "file": "shear_force.png",
                              "title": "cyclic shear: edge force (N) vs edge displacement (mm)"},
                             {"x": "time", "y": "energy.friction", "file": "shear_friction.png",
                              "title": "cyclic shear: friction work (N mm)"}]}
    return s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--settle", action="store_true")
    ap.add_argument("--from", dest="state")
    ap.add_argument("--out", default="samples")
    a = ap.parse_args()
    if a.settle:
        json.dump(settle_scene(), open("/tmp/fabric_settle.json", "w"), indent=1)
        return
    sh = start_shifts(a.state)
    for name, scene in (("fabric_biaxial", biaxial(sh)), ("fabric_shear", shear(sh))):
        with open(f"{a.out}/{name}.json", "w") as f:
            f.write(dump(scene))


def dump(scene):
    """The scene as JSON with a header comment, one line per list item."""
    one = lambda v: json.dumps(v, separators=(", ", ": "))
    parts = []
    for k, v in scene.items():
        if isinstance(v, list) and v:
            parts.append(f'  "{k}": [\n    ' + ",\n    ".join(one(x) for x in v) + "\n  ]")
        else:
            parts.append(f'  "{k}": {one(v)}')
    head = ("// Written by scripts/fabric_loadings.py (docs/SCENE.md \"Fabric test loadings\"): the\n"
            "// per-fibre start positions come from a force-controlled settle run.\n")
    return head + "{\n" + ",\n".join(parts) + "\n}\n"


if __name__ == "__main__":
    main()
