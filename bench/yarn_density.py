#!/usr/bin/env python3
"""Fibre spacing at a yarn's periphery against its centre, from a cross-section's outlines.

Reads the outlines file that `fibra section` writes (FILE.dat: index 0, one block of x y points per
fibre section, blank lines between; index 1 the tools' segments, ignored). For each section: its
centroid (the polygon's area centroid) and area. The yarn's shape is taken from the centroids'
second moments: an ellipse of semi-axes 2 sigma_1, 2 sigma_2 along the principal directions
(a uniformly filled ellipse has sigma = a / 2), and each section's normalised radius rho is its
centroid's ellipse coordinate (rho = 1 on that ellipse). Then, for the sections at the centre
(rho <= 0.5) and at the periphery (rho >= 0.8):
  spacing  the mean distance from a centroid to its 3 nearest neighbours, / (2 R), R the sections'
           mean equivalent radius sqrt(area / pi): 1 for touching circles, 1.1 for the generator's
           hexagonal layout with a gap of 0.1 R;
  density  the sections' area within the region over the region's area (the rings rho <= 0.5 and
           0.8 <= rho <= 1 of the ellipse): the area fraction, the ellipse fitted to the
           centroids, so its outer ring cuts the outermost sections.
Both read a uniform layout as sparser at the periphery (an outer section has fewer neighbours to
pick from, and the outer ring cuts the outermost sections): measured on the generator's start of
the 250-fibre yarn, spacing 1.060 at the centre and 1.100 at the periphery, density 0.716 and
0.612. So a stage is read against the start: the periphery has tightened relative to the centre
when its spacing has fallen, or its density risen, more than the centre's (the paper's Fig. 17
reading: fibres tighter at the periphery after twist and crush). Prints one line per file.

usage: python3 bench/yarn_density.py SECTION.dat [SECTION.dat ...]
"""
import math
import sys


def read_sections(path):
    sections, block, index = [], [], 0
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith('#'):
                continue
            if not line:
                if block:
                    sections.append(block)
                    block = []
                else:  # two blank lines: the next gnuplot index (the tools)
                    index += 1
                continue
            if index == 0:
                x, y = map(float, line.split()[:2])
                block.append((x, y))
    if block and index == 0:
        sections.append(block)
    return sections


def centroid_area(poly):
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    a *= 0.5
    return (cx / (6 * a), cy / (6 * a)), abs(a)


def region_stats(points, areas, rho, radius, lo, hi):
    members = [i for i, r in enumerate(rho) if lo <= r <= hi]
    spacing = []
    for i in members:
        d = sorted(math.dist(points[i], p) for j, p in enumerate(points) if j != i)[:3]
        spacing.append(sum(d) / len(d) / (2 * radius))
    return members, sum(spacing) / len(spacing) if spacing else float('nan')


def analyse(path):
    sections = [s for s in read_sections(path) if len(s) >= 3]
    if len(sections) < 10:
        raise SystemExit(f'{path}: {len(sections)} sections: too few for a centre and a periphery')
    ca = [centroid_area(s) for s in sections]
    points = [c for c, _ in ca]
    areas = [a for _, a in ca]
    n = len(points)
    mx = sum(p[0] for p in points) / n
    my = sum(p[1] for p in points) / n
    sxx = sum((p[0] - mx) ** 2 for p in points) / n
    syy = sum((p[1] - my) ** 2 for p in points) / n
    sxy = sum((p[0] - mx) * (p[1] - my) for p in points) / n
    # principal axes of the 2 x 2 covariance
    tr, det = sxx + syy, sxx * syy - sxy * sxy
    l1 = tr / 2 + math.sqrt(max(tr * tr / 4 - det, 0))
    l2 = tr / 2 - math.sqrt(max(tr * tr / 4 - det, 0))
    theta = 0.5 * math.atan2(2 * sxy, sxx - syy)
    c, s = math.cos(theta), math.sin(theta)
    a1, a2 = 2 * math.sqrt(l1), 2 * math.sqrt(l2)
    rho = []
    for x, y in points:
        u = (x - mx) * c + (y - my) * s
        v = -(x - mx) * s + (y - my) * c
        rho.append(math.hypot(u / a1, v / a2))
    radius = math.sqrt(sum(areas) / n / math.pi)
    ellipse = math.pi * a1 * a2
    out = []
    for name, lo, hi in (('centre', 0.0, 0.5), ('periphery', 0.8, 1.0)):
        members, spacing = region_stats(points, areas, rho, radius, lo, hi)
        area = sum(areas[i] for i in members)
        density = area / (ellipse * (hi * hi - lo * lo))
        out.append(f'{name} {len(members)} sections, spacing {spacing:.3f} (2R), density {density:.3f}')
    print(f'{path}: {n} sections, ellipse {2 * a1:.4f} x {2 * a2:.4f} mm; ' + '; '.join(out))


if __name__ == '__main__':
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    for p in sys.argv[1:]:
        analyse(p)
