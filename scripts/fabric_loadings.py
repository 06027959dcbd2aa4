#!/usr/bin/env python3
"""Writes the reduced woven-fabric test scenes samples/fabric_biaxial.json and
samples/fabric_shear.json (a 2 x 2 plain weave), and with `--weave twill`
samples/fabric_twill_biaxial.json (a 3 x 3 twill, 2 over 1 under) (docs/SCENE.md "Fabric test
loadings").

fibra's boundary conditions hold a DOF for the whole run, so a fibre end cannot slide under a
small tension during the initial geometry and then be driven. The scenes therefore hold every
fibre's start at the x (warp) or y (weft) it reaches in the force-controlled initial geometry
(the yarns' crimp pulls the free starts inward), read from that run's final_state.csv:

  python3 scripts/fabric_loadings.py --settle            # writes /tmp/fabric_settle.json
  fibra run /tmp/fabric_settle.json --out /tmp/fabric_settle --threads 1
  python3 scripts/fabric_loadings.py --from /tmp/fabric_settle/final_state.csv

and for the twill the same three with `--weave twill`:

  python3 scripts/fabric_loadings.py --settle --weave twill   # /tmp/fabric_twill_settle.json
  fibra run /tmp/fabric_twill_settle.json --out /tmp/fabric_twill_settle --threads 1
  python3 scripts/fabric_loadings.py --weave twill --from /tmp/fabric_twill_settle/final_state.csv

Units: mm, N, MPa.
"""
import argparse
import csv
import json
import math

SPACING = 1.5          # between yarn axes, mm
# Per weave: yarns in each direction, the generator's pattern, quadratic elements per fibre
# (0.375 mm each: the fibres are (yarns + 1) x SPACING long).
WEAVES = {"plain": {"yarns": 2, "pattern": "plain", "elements": 12},
          "twill": {"yarns": 3, "pattern": {"weave": "twill", "over": 2, "under": 1},
                    "elements": 16}}
WEAVE = WEAVES["plain"]  # set by --weave
TENSION = 0.01         # N per fibre end, the small tension of the initial geometry
MU = 0.1               # friction between yarns in the loading scenes
STRAIN = 0.004         # biaxial: elongation / length at the end of the test
SHEAR_U = 0.3          # shear: edge displacement amplitude, mm (+-, each edge; --shear-u):
                       # shear angle atan(2 u / 4.5 mm) = +-7.6 deg. At +-1.27 deg (0.05 mm) too
                       # few crossings slid for the dissipation to grow with mu (docs/RESULTS.md)
CYCLES = 2             # shear cycles
QUARTER = 4            # shear increments per quarter cycle
DAMPING = 0.1          # the twill's normal rules: viscous continuation, N/mm x pseudo-time per node
BIAXIAL_DAMPING = 0.01 # the twill's biaxial tension, same unit
SHEAR_DAMPING = 0.01   # shear, same unit (0.1 doubles the edge force at u = 0.3 mm)


def length():
    """Of every fibre, mm: the generator's default, one spacing beyond the outer yarns."""
    return (WEAVE["yarns"] + 1) * SPACING


def fabric():
    yarn = {"yarns": WEAVE["yarns"], "spacing": SPACING, "fibres_per_yarn": 3,
            "fibre_radius": 0.1, "gap": 0.01, "material": "polymer",
            "elements": WEAVE["elements"]}
    return {"type": "woven_fabric", "name": "fab", "pattern": WEAVE["pattern"],
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
    return [f"fab.{d}{y}.f{k}" for d in ("warp", "weft") for y in range(WEAVE["yarns"])
            for k in range(3)]


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
    s["tables"] = {"one": [[0, 1], [loading_start(), 1]]}
    s["steps"] = initial_steps()
    s["output"] = {"vtu": False}
    return s


def initial_steps():
    """Forced normals, then the normal rules, both frictionless (friction_factor 0: friction
    breaks the forced step); the loading steps that follow have the scene's friction. The
    twill's yarns move further when the normal rules come back (its floats): they come back
    damped, in 4 increments, and an undamped step settles the fabric; in one undamped increment
    the fibres slid by 1.5 R and more under elements detected before, and no new detection
    closed the set (inconsistent contact set; nothing changes over the step, so a cutback
    repeats the same attempt and the step fails at once). The settle
    step's second increment changes no load: it starts from a detection at the settled state,
    whose elements the first one's large motion had left behind (true overlap 1.24 p_max after
    one increment, within the acceptance check's 1.5)."""
    steps = [{"name": "initial_geometry", "end_time": 1, "increments": 4,
              "forced_normals": {"direction": [0, 0, 1]}, "friction_factor": 0}]
    if WEAVE["pattern"] == "plain":
        return steps + [{"name": "normal_rules", "end_time": 2, "increments": 1,
                         "friction_factor": 0}]
    return steps + [{"name": "normal_rules", "end_time": 2, "increments": 4, "damping": DAMPING,
                     "friction_factor": 0},
                    {"name": "settle", "end_time": 3, "increments": 2, "friction_factor": 0}]


def loading_start():
    """Time at which the initial geometry ends and the loading starts."""
    return initial_steps()[-1]["end_time"]


def start_shifts(final_state):
    """Each fibre's start displacement along its yarn (mm) at the end of the settle run."""
    out = {}
    with open(final_state) as f:
        for row in csv.DictReader(f):
            if row["node"] != "0":
                continue
            warp = ".warp" in row["fibre"]
            start = float(row["x"] if warp else row["y"])
            out[row["fibre"]] = start + length() / 2
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
    s = base(f"{title()}, 3 fibres per yarn: initial geometry, then biaxial tension "
             "(equal elongation in warp and weft, 20 increments)")
    s["contact"]["pairs"].append({"classes": ["fab.warp", "fab.weft"], "friction": MU})
    L = length()
    t0 = loading_start()
    stretch = lambda c: [[0, 0], [0.25, c], [t0, c], [t0 + 1, c - STRAIN * L]]
    s["boundary_conditions"] = [
        {"type": "fix", "group": "fab.warp.end", "dofs": ["x0", "g1y"]},
        {"type": "fix", "group": "fab.weft.end", "dofs": ["x0", "g1x"]},
        {"type": "fix", "group": "fab.warp.start", "dofs": ["y"]},
        {"type": "fix", "group": "fab.weft.start", "dofs": ["x"]}] + held_starts(shifts, stretch)
    tension = {"name": "biaxial_tension", "end_time": t0 + 1, "increments": 20}
    if WEAVE["pattern"] != "plain":
        # Undamped, the twill's second increment stagnates at a relative residual of 0.14 after
        # 8 cutbacks; with this damping the viscous force ends at 2.4e-3 of the reference force.
        tension["damping"] = BIAXIAL_DAMPING
        # Frictionless crossings follow their closest points in loop B: the settle ends at 0.87
        # p_max of overlap between yarns instead of 1.16 (docs/CONTACT.md "Crossings that follow").
        s["contact"]["follow_crossings"] = True
    s["steps"] = initial_steps() + [tension]
    s["output"] = {"vtu": False, "probes": [{"name": "warp_start", "fibre": "fab.warp0.f0",
                                             "node": 0}],
                   "plots": [{"x": "probe.warp_start.x",
                              "y": ["reaction.fab.warp.end.fx", "reaction.fab.weft.end.fy"],
                              "file": "biaxial_force.png",
                              "title": "biaxial tension: edge force (N) vs warp start x (mm)"}]}
    return s


def shear(shifts):
    s = base(f"{title()}, 3 fibres per yarn: initial geometry, then cyclic shear "
             "(the warp yarns' ends moved in opposite directions along y, alternately)")
    s["contact"]["pairs"].append({"classes": ["fab.warp", "fab.weft"], "friction": MU})
    hold = lambda c: [[0, 0], [0.25, c]]
    t0 = loading_start()
    cycle = [[t0, 0]]
    for k in range(CYCLES):
        t = t0 + 4 * k
        cycle += [[t + 1, SHEAR_U], [t + 3, -SHEAR_U]]
    cycle.append([t0 + 4 * CYCLES, 0])
    s["tables"] = {"cycle": cycle}
    s["boundary_conditions"] = [
        {"type": "fix", "group": "fab.warp.end", "dofs": ["x0", "g1y"],
         "displacement": [0, -1, 0], "table": "cycle"},
        {"type": "fix", "group": "fab.weft.end", "dofs": ["x0", "g1x"]},
        {"type": "fix", "group": "fab.warp.start", "dofs": ["y"],
         "displacement": [0, 1, 0], "table": "cycle"},
        {"type": "fix", "group": "fab.weft.start", "dofs": ["x"]}] + held_starts(shifts, hold)
    steps = initial_steps()
    t = t0
    quarters = [(1, QUARTER)] + [(2, 2 * QUARTER)] * (2 * CYCLES - 1) + [(1, QUARTER)]
    for k, (dt, n) in enumerate(quarters):
        t += dt
        steps.append({"name": f"shear_{k}", "end_time": t, "increments": n, "damping": SHEAR_DAMPING})
    s["steps"] = steps
    s["output"] = {"vtu": False, "probes": [{"name": "warp_start", "fibre": "fab.warp0.f0",
                                             "node": 0}],
                   "plots": [{"x": "probe.warp_start.y", "y": "reaction.fab.warp.end.fy",
                              "file": "shear_force.png",
                              "title": "cyclic shear: edge force (N) vs edge displacement (mm)"},
                             {"x": "time", "y": "energy.friction", "file": "shear_friction.png",
                              "title": "cyclic shear: friction work (N mm)"}]}
    return s


def title():
    n = WEAVE["yarns"]
    return f"{n} x {n} plain weave" if WEAVE["pattern"] == "plain" else f"{n} x {n} twill (2/1)"


def main():
    global WEAVE, SHEAR_U
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--settle", action="store_true",
                    help="write the force-controlled settle scene to /tmp (see above) and stop")
    ap.add_argument("--from", dest="state", metavar="FINAL_STATE_CSV",
                    help="the settle run's final_state.csv: the fibre starts' positions")
    ap.add_argument("--out", default="samples",
                    help="directory the loading scenes are written to (default: samples)")
    ap.add_argument("--shear-u", type=float, default=SHEAR_U, metavar="MM",
                    help=f"shear amplitude, each edge (default {SHEAR_U} mm; 0.8 mm is the "
                         "paper's +-20 deg)")
    ap.add_argument("--weave", choices=sorted(WEAVES), default="plain",
                    help="plain: fabric_biaxial.json and fabric_shear.json (2 x 2); "
                         "twill: fabric_twill_biaxial.json (3 x 3) (default: plain)")
    a = ap.parse_args()
    if not a.settle and not a.state:
        ap.error("--from FINAL_STATE_CSV is needed (or --settle to write the settle scene)")
    WEAVE = WEAVES[a.weave]
    if not (a.shear_u > 0 and math.isfinite(a.shear_u)):
        ap.error(f"--shear-u must be a positive displacement in mm, not {a.shear_u}")
    SHEAR_U = a.shear_u
    plain = a.weave == "plain"
    if a.settle:
        path = "/tmp/fabric_settle.json" if plain else f"/tmp/fabric_{a.weave}_settle.json"
        json.dump(settle_scene(), open(path, "w"), indent=1)
        return
    sh = start_shifts(a.state)
    scenes = ((("fabric_biaxial", biaxial(sh)), ("fabric_shear", shear(sh))) if plain
              else ((f"fabric_{a.weave}_biaxial", biaxial(sh)),))
    for name, scene in scenes:
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
