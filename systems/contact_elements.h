// Contact element generator: intermediate geometries (eq. 5) and contact elements (eqs. 6-9).
//
// Reads  FibreStore, the state q (x0, g1, g2), ContactParams, CentrelineStore, ZoneStore
//        (fibres, intervals, refined), the cancel flag (per chunk of zones).
// Writes ZoneStore::intermediateLength, firstElement, elementCount; ContactElementStore (zone,
//        zeta, length, weight, particles, normal, gap, theta, crossWeight (eqs. 10-11,
//        systems/contact_normals.h), fallback bits, forced, crossing; every other column is sized
//        and left to the systems after it).
// Threading: parallel over zones, twice: lengths, then (after a prefix sum of the counts) the
//        elements, each zone writing its own range. Independent of the thread count.
//
// Per zone Z = ([sI1, sI2], [sJ1, sJ2]), with sI(zeta) = sI1 + zeta (sI2 - sI1) (same on J):
//   x_int(zeta) = (x_I(sI(zeta)) + x_J(sJ(zeta))) / 2,  t_int = dx_int / dzeta          (eq. 5)
//   L_int = int_0^1 |t_int| dzeta: two-point Gauss on each piece between the element ends of I
//   and J (t_int is linear in zeta on a piece), 0 for a zero-length zone;
//   (L_int and the placement below: systems/contact_intermediate.h)
//   point or line: floor(2 L_int / h_min) < 2 (eq. 6), h_min = min(h_I, h_J): one element at
//     zeta = 1/2 of length L_int. Else a line contact, whose elements are weighted (eq. 7
//     replaced): the zone is cut at the element ends of both fibres (a cut within h_min / 10 of
//     arc length of the last kept cut or of the zone's end is dropped), each piece [a, b]
//     carries the two Gauss points zeta = (a + b) / 2 -+ (b - a) / (2 sqrt 3), each of length
//     l_k = (b - a) / 2 |t_int(zeta_k)| (mm) and weight w_k = l_k Nc / sum l (mean 1), which
//     scales the zone's penalty on it. A uniform line pressure p then loads the nodes of both
//     fibres with the consistent line load int N_a p ds exactly: a uniform line load is
//     carried as a uniform line force at any p_max (equal point forces at the eq. 7 spacing gave
//     +-5%, Gauss points of one fibre only +-9% on the other when their grids are offset).
//     ElementPlacement::Lobatto instead: each piece's ends and midpoint with Simpson's
//     lengths (b - a)/6, 4 (b - a)/6, (b - a)/6 times |t_int| (shared cuts one element), the
//     piece cut into m <= 8 Simpson sub-pieces where the gap g(zeta) may dip by more than
//     p_max / 4 between samples (K dzeta^2 / 8, K = |D''| + |D'_perp|^2 / |D| estimated,
//     D = x_I - x_J); every kept cut, so every element end of either fibre but those within
//     h_min / 10 of another cut, then carries an element. A section within 1e-3 h of an
//     interior node takes the element its neighbour in zeta pairs with the other fibre's (1e-7 h
//     inside it), so no new pair of beam elements is coupled. Paper: eq. 7 (equal spacing and
//     weights). A zone the acceptance refined (ZoneStore::refined, under "weighted" only) takes
//     the Lobatto elements.
//   sections: (x(s) - x_int(zeta_k)) . t_int(zeta_k) = 0 on I and on J                   (eq. 8)
//     by Newton from sI(zeta_k) (resp. sJ) within the zone interval widened by Delta_prox
//     (clamped to the fibre), bisection as safeguard; then, where both cuts are well posed,
//     moved within the plane to the nearest pair (its midpoint kept in the plane) when that
//     brings the centres closer by more than p_max / 10 (systems/contact_sections.h: a tilted
//     plane cuts a fibre wound round another away from where they touch); for a point
//     element then moved to the local minimum of the centreline distance |x_I(sI) - x_J(sJ)|
//     near them (Newton in (sI, sJ), kept when it converges inside both widened intervals to a
//     minimum, the fibres make more than theta_parallel there and, in self-contact, sJ - sI is
//     at least the separation): on curved crossings the eq. 8 plane misses the closest points
//     when the zone's test point does (0.05 mm off at a woven crossing, reporting 0.65 p_max
//     where the fibres overlapped by 9 p_max);
//   particles: on each section, the outline point x0 + xi1 g1 + xi2 g2, |xi| = R, in the
//     direction of the other section's centre projected onto span(g1, g2)        (eq. 9, Fig. 4).
//   Self-contact (I == J) takes every rule here, the crossings' and the ends' included, with
//     sJ >= sI + separation: a fibre that crosses over itself is a crossing of two strands, and
//     its end touches its own side as another fibre's would (without them a loop crossing over
//     itself at its symmetry reported none of its 3.7e-4 mm overlap, and a hooked end none of
//     its 3e-4 mm: tests/test_contact_minima.cpp).
//   Minima of a zone: the local minima of the centreline distance, by the Newton above from the
//     eq. 8 sections at zeta = 1/2 and from the zone's linear map at zeta = k / n (n = ceil(8
//     L_int / h_min) in [4, 256]; long zones only where the fibres cross, |t_I x t_J| >
//     sin theta_parallel); a minimum past a fibre's end is sought at that end (the end section
//     held, systems/contact_sections.h), so an end's rim under a crossing fibre gets an element
//     on its end face. A long zone's narrow ones (the patch a penetration p_max spans shorter
//     than the element spacing) and its end-held ones where the fibres make more than
//     theta_cross (not a line contact's converging end) each take the nearest element; a point
//     zone has an element at each of its minima whose centres lie within R_I + R_J + 2 p_max
//     (L_int / m each for m of them; none: its one element from zeta = 1/2 as above): a strand
//     bent round another more tightly than their distance comes closest to it twice, and one
//     element at one minimum let the strands through at the other.
//   Flat ends: when a section is an end of its fibre and the other section's centre lies beyond
//     that end's plane (by more than 1e-9 R), the particle is the point of the end face closest
//     to that centre, xi = m clamped to |xi| <= R, G m the projection of the centre onto the
//     section plane; the other particle is the outline point facing it; N is normal to the other
//     fibre's axis through it (kEndFaceI / kEndFaceJ, systems/contact_normals.h). So no contact
//     exists past an end, and an end's face and rim touch the other fibre's side. (Two ends
//     facing each other are not modelled: docs/CONTACT.md, after the fallback table.)
//   Forced normals (a step's forced_normals; systems/contact_normals.h): when the element's
//     fibres are of different classes with different levels at sI, sJ, N = sign D and the
//     particles are the outline points facing along N instead (I's towards -N, J's towards +N),
//     with no end-face rule; centrelines that cross (coincident centres) are no special case.
//     The sign is decided here, once, and kept in ContactElementStore::forced: loop B, the law
//     and the acceptance read it there.
//
// Degenerate cases (documented in docs/CONTACT.md, flagged in ContactElementStore::fallback):
//   t_int = 0 (zero-length zone, or cancelling pieces): t_int := bisector of the tangents
//     t_I + t_J (t_J flipped to t_I's side).
//   Eq. 8 ill-posed on one fibre (its tangent makes more than 80 deg with t_int, so the plane
//     nearly contains it - e.g. J in a perpendicular crossing where J's interval shrinks to a
//     point - or no root in its widened interval - e.g. the fibre ends inside the zone): that
//     section is the closest point, within the widened interval, to the other section's centre.
//     Both ill-posed: I at sI(zeta_k), J closest to it.
//   The other centre has no component in the section plane (coincident or end-to-end centres):
//     the particle is taken in the direction -n on I and +n on J, n = t_I x t_J, or the
//     direction of I's director g1 when the fibres are parallel.
#pragma once

#include "components/contact_cache.h"
#include "core/cancel.h"
#include "core/trace.h"
#include "systems/contact_params.h"

namespace fibra {

// Cancelled (checked per chunk of zones): returns early with some zones' elements left unset.
void generateContactElements(const FibreStore& fs, const Eigen::VectorXd& q,
                             const ContactParams& params, const CentrelineStore& centrelines,
                             ZoneStore& zones, ContactElementStore& elements, Trace* trace,
                             const Cancel& cancel);

}  // namespace fibra
