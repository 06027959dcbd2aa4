#!/usr/bin/env python3
"""Brute-force true overlap of a run's fibres, from its final_state.csv (independent of the
contact elements): every fibre's centreline and directors sampled at --samples points per
element (fibres of quadratic elements, fibra's default: Lagrange interpolation of the three nodes), every pair of samples
on different fibres, or on one fibre more than --min-elements elements apart (self-contact),
within --reach mm; each pair closer than 2.2 R is refined to the closest points of the two
centrelines near it (alternating golden-section searches within one sample spacing), so a
crossing between samples is not missed, and measured there: w_a + w_b - d with d the distance of
the two points and w = R |G^T n| each fibre's half-width along n = the direction between them
(G = [g1 g2]), normal to both centrelines at closest points, where a section's width along n is
the tube's (a pair the search left elsewhere, n more than 1e-3 off normal, is not measured,
but for nearly parallel fibres, within 5 degrees, which have no closest pair: across the mean
tangent, d less its part along it). Where the closest point lies at a fibre's end (the search stopped there), that
direction runs along the fibre and says nothing of its width: the end's flat disc x0 + G xi,
|xi| <= R (5 rings of 72 points) is measured instead, each point's depth in the other fibre
w - d (d its distance from the nearest point of the other centreline, w that fibre's half-width
along it), the deepest. One radius for every fibre (--radius). Prints the largest overlap (mm and
in units of --pmax) and where it is.

  python3 bench/centreline_overlap.py out/plectoneme/final_state.csv --radius 0.1 \
      --pmax 5e-4 --min-elements 4
"""
import argparse
import csv
import math
from collections import defaultdict


def load_fibres(path, columns=("x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z")):
    """{fibre: [[column values] per node]} from a run's final_state.csv; exits with a message
    naming the file and what is wrong (missing, not a final state, no rows, or a fibre whose node
    count is even: these scripts take fibres of quadratic elements, 2 n + 1 nodes)."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            missing = [c for c in ("fibre",) + tuple(columns) if c not in (reader.fieldnames or [])]
            if missing:
                raise SystemExit(f"{path}: not a final_state.csv (no column {', '.join(missing)})")
            fibres = defaultdict(list)
            for line, r in enumerate(reader, start=2):
                try:
                    fibres[r["fibre"]].append([float(r[k]) for k in columns])
                except (TypeError, ValueError):
                    raise SystemExit(f"{path}:{line}: a value is missing or not a number")
    except OSError as e:
        raise SystemExit(f"{path}: {e.strerror}")
    if not fibres:
        raise SystemExit(f"{path}: no nodes")
    for name, rows in fibres.items():
        if len(rows) < 3 or len(rows) % 2 == 0:
            raise SystemExit(f"{path}: fibre {name} has {len(rows)} nodes; these scripts take "
                             "fibres of quadratic elements (2 n + 1 nodes)")
    return fibres


def section(rows, u):
    """(x0, g1, g2) at element coordinate u in [0, elements] of a fibre of quadratic elements."""
    elements = (len(rows) - 1) // 2
    e = min(int(u), elements - 1)
    z = 2 * (u - e) - 1
    N = (z * (z - 1) / 2, 1 - z * z, z * (z + 1) / 2)
    v = [sum(N[a] * rows[2 * e + a][c] for a in range(3)) for c in range(9)]
    return v[0:3], v[3:6], v[6:9]


def samples(rows, per_element):
    """[(element coordinate, x0, g1, g2)] along one fibre."""
    elements = (len(rows) - 1) // 2
    return [(u,) + section(rows, u)
            for u in (k / per_element for k in range(elements * per_element + 1))]


def golden(f, a, b, iterations=30):
    """Argmin of f on [a, b] by golden-section search."""
    r = (math.sqrt(5) - 1) / 2
    c, d = b - r * (b - a), a + r * (b - a)
    for _ in range(iterations):
        if f(c) < f(d):
            b, d = d, c
            c = b - r * (b - a)
        else:
            a, c = c, d
            d = a + r * (b - a)
    return (a + b) / 2


def refine(rows_a, ua, rows_b, ub, step):
    """The closest points of two centrelines near (ua, ub), within `step` of them."""
    la, lb = (len(rows_a) - 1) // 2, (len(rows_b) - 1) // 2
    dist = lambda u, v: math.dist(section(rows_a, u)[0], section(rows_b, v)[0])
    a0, b0 = ua, ub
    for _ in range(60):  # alternating sweeps contract by about cos^2 of the angle: up to 60
        pa, pb = ua, ub
        ua = golden(lambda u: dist(u, ub), max(0, a0 - step), min(la, a0 + step))
        ub = golden(lambda v: dist(ua, v), max(0, b0 - step), min(lb, b0 + step))
        if abs(ua - pa) + abs(ub - pb) < 1e-9:
            break
    return ua, ub


def tangent(rows, u, h=1e-6):
    """The centreline's unit tangent at element coordinate u (central differences)."""
    elements = (len(rows) - 1) // 2
    a, b = section(rows, max(0, u - h))[0], section(rows, min(elements, u + h))[0]
    d = math.dist(a, b)
    return [(y - x) / d for x, y in zip(a, b)]


def half_width(g1, g2, n, radius):
    dot = lambda a, b: sum(x * y for x, y in zip(a, b))
    return radius * math.hypot(dot(g1, n), dot(g2, n))


def disc_depth(rows_e, ue, rows_o, uo, radius):
    """The deepest point of the end disc of fibre rows_e (at ue, an end) in fibre rows_o, near uo:
    over x0 + xi1 g1 + xi2 g2 on 5 rings (|xi| = 0, R/4 .. R) of 72 points, w - d with d the
    distance to the closest point of the other centreline (golden search within one element of
    uo) and w that fibre's half-width along it; mm, negative when the disc is clear."""
    x0, g1, g2 = section(rows_e, ue)
    lo = (len(rows_o) - 1) // 2
    deepest = -math.inf
    for ring in range(5):
        r = radius * ring / 4
        for k in range(72 if ring else 1):
            c, s = r * math.cos(math.pi * k / 36), r * math.sin(math.pi * k / 36)
            p = [x0[i] + c * g1[i] + s * g2[i] for i in range(3)]
            v = golden(lambda w: math.dist(section(rows_o, w)[0], p), max(0, uo - 1), min(lo, uo + 1))
            xo, h1, h2 = section(rows_o, v)
            d = math.dist(p, xo)
            if d == 0:
                return radius
            n = [(p[i] - xo[i]) / d for i in range(3)]
            deepest = max(deepest, half_width(h1, h2, n, radius) - d)
    return deepest


def state_parser(doc, samples):
    """The arguments both overlap scripts take: a final state, R, p_max, samples per element."""
    p = argparse.ArgumentParser(description=doc.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("final_state")
    p.add_argument("--radius", type=float, required=True, help="fibre radius R, mm")
    p.add_argument("--pmax", type=float, default=0, help="p_max, mm (for the ratio)")
    p.add_argument("--samples", type=int, default=samples, help="samples per element")
    return p


def main():
    p = state_parser(__doc__, 16)
    p.add_argument("--min-elements", type=float, default=4,
                   help="self-contact: pairs on one fibre at least this many elements apart")
    p.add_argument("--reach", type=float, default=0, help="pairs within this distance, mm (0: 2.5 R)")
    a = p.parse_args()
    if a.samples < 1 or not a.radius > 0 or not a.pmax >= 0:
        p.error("--samples must be >= 1, --radius > 0 and --pmax >= 0")
    fibres = load_fibres(a.final_state)
    pts = [(f, s) for f, rows in fibres.items() for s in samples(rows, a.samples)]
    reach = a.reach or 2.5 * a.radius
    best = (0.0, None, None)

    def at_end(f, u):
        return u <= 1e-5 or u >= (len(fibres[f]) - 1) // 2 - 1e-5

    def consider(fi, ui, fj, uj):
        nonlocal best
        xi, g1i, g2i = section(fibres[fi], ui)
        xj, g1j, g2j = section(fibres[fj], uj)
        if at_end(fi, ui) or at_end(fj, uj):
            overlap = (disc_depth(fibres[fi], ui, fibres[fj], uj, a.radius) if at_end(fi, ui)
                       else disc_depth(fibres[fj], uj, fibres[fi], ui, a.radius))
        else:
            d = math.dist(xi, xj)
            if d == 0:
                return
            n = [(p - q) / d for p, q in zip(xi, xj)]
            # a pair the search left short of the closest points: n runs along a fibre there,
            # where a section's width is not the fibre's. Crossing fibres: not measured (another
            # sample pair reaches their closest points); nearly parallel ones (within 5 deg),
            # which have no closest pair: d's part across the mean tangent
            ti, tj = tangent(fibres[fi], ui), tangent(fibres[fj], uj)
            if max(abs(sum(x * y for x, y in zip(n, t))) for t in (ti, tj)) > 1e-3:
                cross = [ti[1] * tj[2] - ti[2] * tj[1], ti[2] * tj[0] - ti[0] * tj[2],
                         ti[0] * tj[1] - ti[1] * tj[0]]
                if math.sqrt(sum(x * x for x in cross)) > math.sin(math.radians(5)):
                    return
                sign = 1 if sum(x * y for x, y in zip(ti, tj)) >= 0 else -1
                t = [x + sign * y for x, y in zip(ti, tj)]
                tn = math.sqrt(sum(x * x for x in t))
                dv = [p - q for p, q in zip(xi, xj)]
                along = sum(x * y / tn for x, y in zip(dv, t))
                dv = [x - along * y / tn for x, y in zip(dv, t)]
                d = math.sqrt(sum(x * x for x in dv))
                if d == 0:
                    return
                n = [x / d for x in dv]
            overlap = half_width(g1i, g2i, n, a.radius) + half_width(g1j, g2j, n, a.radius) - d
        if overlap > best[0]:
            best = (overlap, (fi, ui, xi), (fj, uj, xj))

    for i in range(len(pts)):
        fi, (ei, xi, _, _) = pts[i]
        for j in range(i + 1, len(pts)):
            fj, (ej, xj, _, _) = pts[j]
            if fi == fj and abs(ei - ej) < a.min_elements:
                continue
            d = math.dist(xi, xj)
            if d == 0 or d > min(reach, 2.2 * a.radius):
                continue
            ui, uj = refine(fibres[fi], ei, fibres[fj], ej, 1 / a.samples)
            if fi != fj or abs(ui - uj) >= a.min_elements:
                consider(fi, ui, fj, uj)
    overlap, A, B = best
    ratio = f" ({overlap / a.pmax:.2f} p_max)" if a.pmax > 0 else ""
    print(f"largest overlap {overlap:.4g} mm{ratio}")
    if A:
        for f, e, x in (A, B):
            print(f"  fibre {f}, element coordinate {e:.3f}, at ({x[0]:.4f}, {x[1]:.4f}, {x[2]:.4f})")


if __name__ == "__main__":
    main()
