#!/usr/bin/env python3
"""End faces pushed onto a fibre: a family of tees, each run and measured independently.

A (R = 0.1 mm, E = 4000 MPa) is a straight line along x, or an arc of radius 0.5 mm (a helix of
pitch 0.001 mm) pressed on its convex or concave side, clamped at both ends; B (the same
section, 2 mm long) stands on A with its end `gap0` = 0.02 mm above touch, its axis tilted by
`tilt` degrees along A, across A or about the diagonal, and its top is driven towards A by
gap0 + push in `inc` increments. For every scene and binary this prints the outcome, and at the
last converged state the depth of B's end disc in A measured from final_state.csv alone (the
disc |xi| <= R on a polar grid of 10 x 72 points refined by a compass search, each point's
distance to A's centreline, quadratic or linear interpolation of the nodes, by 4000 samples and
a golden-section search, less A's deformed half-width R |G^T n| along the offset: in p_max =
0.005 R), beside the history's reported
penetration and the acceptance's overlap (contact.max_penetration, contact.max_overlap).

    python3 bench/end_faces.py --fibra build/fibra [--old OLD_BINARY] [--only NAME ...] [--keep DIR]
"""
import argparse, csv, json, math, os, subprocess, sys, tempfile

R, PMAX = 0.1, 5e-4


def scene(tilt=10.0, axis="along", push=0.05, mu=0.0, elements=10, order=2, other="line",
          side="out", inc=20, gap0=0.02):
    a = math.radians(tilt)
    if other == "line":
        up, along, across = (0, 0, 1), (1, 0, 0), (0, 1, 0)
        geo = {"type": "line", "points": [[-2, 0, 0], [2, 0, 0]], "director": [0, 0, 1]}
    else:  # an arc of radius 0.5 in the x-y plane whose top (or bottom, concave) is the origin
        rc, half = 0.5, 0.8 / 0.5
        centre, phase = ((0, -rc, 0), math.pi / 2 - half) if side == "out" else ((0, rc, 0), -math.pi / 2 - half)
        up, along, across = (0, 1, 0), (1, 0, 0), (0, 0, 1)  # B above: outside or inside the arc
        geo = {"type": "helix", "radius": rc, "pitch": 0.001, "turns": 2 * half / (2 * math.pi),
               "origin": list(centre), "phase": phase}
    t = {"along": (math.sin(a), 0, math.cos(a)), "across": (0, math.sin(a), math.cos(a)),
         "diagonal": (math.sin(a) / 2 ** 0.5, math.sin(a) / 2 ** 0.5, math.cos(a))}[axis]
    u = [t[0] * along[i] + t[1] * across[i] + t[2] * up[i] for i in range(3)]
    zE = R + R * math.sin(a) + gap0
    E = [zE * up[i] for i in range(3)]
    d = list(along) if axis == "across" else list(across)
    return {"units": "mm-N-MPa",
            "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
            "fibres": [{"name": "A", "material": "m", "radius": R, "elements": elements, "order": order, "geometry": geo},
                       {"name": "B", "material": "m", "radius": R, "elements": elements, "order": order,
                        "geometry": {"type": "line", "points": [E, [E[i] + 2 * u[i] for i in range(3)]], "director": d}}],
            "boundary_conditions": [{"type": "clamp", "group": "A.start"}, {"type": "clamp", "group": "A.end"},
                                    {"type": "clamp", "group": "B.end", "displacement": [-(gap0 + push) * up[i] for i in range(3)]}],
            "contact": {"friction": mu} if mu else {},
            "steps": [{"end_time": 1, "increments": inc}]}


SCENES = {}
for ax in ("along", "across", "diagonal"):
    for tl in (3, 10, 30, 60):
        for mu in (0.0, 0.3):
            SCENES[f"{ax}_t{tl}_mu{mu:g}"] = dict(tilt=tl, axis=ax, mu=mu)
SCENES.update({
    "along_t10_order1": dict(tilt=10, order=1), "along_t10_40el": dict(tilt=10, elements=40),
    "along_t10_4el": dict(tilt=10, elements=4), "diagonal_t30_40el": dict(tilt=30, axis="diagonal", elements=40),
    "arc_out_t0_mu0.3": dict(tilt=0, other="arc", mu=0.3), "arc_out_t20_mu0.3": dict(tilt=20, other="arc", mu=0.3),
    "arc_in_t0_mu0.3": dict(tilt=0, other="arc", side="in", mu=0.3), "arc_in_t20_mu0": dict(tilt=20, other="arc", side="in"),
    "arc_in_t20_mu0.3": dict(tilt=20, other="arc", side="in", mu=0.3),
})


def nodes(path):
    out = {}
    for r in csv.DictReader(open(path)):
        out.setdefault(r["fibre"], []).append([float(r[k]) for k in ("x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z")])
    return out


def interpolated(n, order, u, offset=0):  # u in [0, elements]; offset 0: x0, 3: g1, 6: g2
    ne = (len(n) - 1) // order
    e = min(ne - 1, max(0, int(math.floor(u))))
    xi = 2 * (u - e) - 1
    if order == 1:
        s = (xi + 1) / 2
        return [(1 - s) * n[e][offset + i] + s * n[e + 1][offset + i] for i in range(3)]
    N = (0.5 * xi * (xi - 1), 1 - xi * xi, 0.5 * xi * (xi + 1))
    return [sum(N[k] * n[2 * e + k][offset + i] for k in range(3)) for i in range(3)]


def centreline(n, order, u):
    return interpolated(n, order, u)


def disc_depth(path, order):
    f = nodes(path)
    A, B = f["A"], f["B"]
    ne = (len(A) - 1) // order
    samples = [centreline(A, order, ne * i / 4000) for i in range(4001)]
    end = B[0]

    def dist(p):  # A's surface from p along the offset from its nearest centreline point (A's
        # deformed section's half-width R |G^T n| there, less the distance): minus the depth
        i = min(range(4001), key=lambda k: (samples[k][0] - p[0]) ** 2 + (samples[k][1] - p[1]) ** 2 + (samples[k][2] - p[2]) ** 2)
        lo, hi = ne * max(0, i - 1) / 4000, ne * min(4000, i + 1) / 4000
        g = (math.sqrt(5) - 1) / 2
        for _ in range(50):
            m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
            if math.dist(p, centreline(A, order, m1)) < math.dist(p, centreline(A, order, m2)): hi = m2
            else: lo = m1
        u = 0.5 * (lo + hi)
        if math.dist(p, samples[i]) < math.dist(p, centreline(A, order, u)): u = ne * i / 4000
        c = centreline(A, order, u)
        r = math.dist(p, c)
        n = [(p[k] - c[k]) / r for k in range(3)] if r > 0 else [0, 0, 1]
        g1, g2 = interpolated(A, order, u, 3), interpolated(A, order, u, 6)
        width = R * math.hypot(sum(g1[k] * n[k] for k in range(3)), sum(g2[k] * n[k] for k in range(3)))
        return r - width + R

    def point(a, b):
        return [end[i] + a * end[3 + i] + b * end[6 + i] for i in range(3)]

    best, ba, bb = dist(point(0, 0)), 0.0, 0.0
    for r in range(1, 11):
        for j in range(72):
            a, b = R * r / 10 * math.cos(j * math.pi / 36), R * r / 10 * math.sin(j * math.pi / 36)
            d = dist(point(a, b))
            if d < best: best, ba, bb = d, a, b
    h = R / 10
    while h > 1e-7:
        moved = False
        for k in range(8):
            a, b = ba + h * math.cos(k * math.pi / 4), bb + h * math.sin(k * math.pi / 4)
            if math.hypot(a, b) > R: a, b = a * R / math.hypot(a, b), b * R / math.hypot(a, b)
            d = dist(point(a, b))
            if d < best - 1e-15: best, ba, bb, moved = d, a, b, True
        if not moved: h *= 0.5
    return (R - best) / PMAX


def run(binary, path, out):
    p = subprocess.run([binary, "run", path, "--out", out, "--threads", "1", "--quiet"], capture_output=True, text=True)
    last = [l for l in (p.stdout + p.stderr).splitlines() if l.startswith("fibra: ")]
    what = last[-1] if last else f"rc {p.returncode}"
    status = "solved" if "solved" in what else ("failed at t = " + what.split("t = ")[1].split(",")[0] if "t = " in what else what)
    row = {"status": status, "iterations": what.split(" Newton")[0].split(", ")[-1] if "Newton" in what else "-"}
    if os.path.exists(f"{out}/final_state.csv"):
        h = list(csv.DictReader(open(f"{out}/history.csv")))
        row["reported"] = float(h[-1]["contact.max_penetration"]) / PMAX if h else 0
        row["accepted"] = float(h[-1]["contact.max_overlap"]) / PMAX if h else 0
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fibra", default="build/fibra")
    ap.add_argument("--old", help="a second binary, run beside")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--keep")
    args = ap.parse_args()
    tmp = args.keep or tempfile.mkdtemp()
    os.makedirs(tmp, exist_ok=True)
    bins = [("now", args.fibra)] + ([("old", args.old)] if args.old else [])
    print("| scene | " + " | ".join(f"{n}: outcome, Newton iterations | {n}: disc depth / reported / acceptance, p_max" for n, _ in bins) + " |")
    print("| --- | " + " | ".join("--- | ---" for _ in bins) + " |")
    for name, kw in SCENES.items():
        if args.only and name not in args.only: continue
        path = f"{tmp}/{name}.json"
        json.dump(scene(**kw), open(path, "w"), indent=1)
        cells = []
        for tag, binary in bins:
            out = f"{tmp}/{name}.{tag}"
            r = run(binary, path, out)
            depth = disc_depth(f"{out}/final_state.csv", kw.get("order", 2)) if "reported" in r else float("nan")
            cells.append(f"{r['status']}, {r['iterations']} | {depth:.2f} / {r.get('reported', float('nan')):.2f} / {r.get('accepted', float('nan')):.2f}")
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
