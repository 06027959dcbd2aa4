// Geometric kernels of the contact detection, shared by its stages: centreline evaluation from
// the per-element polynomials, closest point of a centreline to a point, the plane cut of
// eq. 8, and the particle on a deformed section outline (paper Fig. 4). Header-only, pure
// functions of their arguments.
#pragma once

#include "components/contact_cache.h"
#include "systems/interpolation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace fibra {

// Polynomial of a node-interpolated centreline, from the element's nodal x0:
//   quadratic: x(z) = x1 + (x2 - x0)/2 z + ((x0 + x2)/2 - x1) z^2;  linear: (x0+x1)/2 + (x1-x0)/2 z.
inline CentrelinePolynomial centrelinePolynomial(const FibreStore& fs, const Eigen::VectorXd& q,
                                                 Index e) {
  const Index n = fs.elementFirstNode[e];
  if (fs.order[fs.elementFibre[e]] == 1) {
    const Vec3 x0 = x0Of(q, n), x1 = x0Of(q, n + 1);
    return {0.5 * (x0 + x1), 0.5 * (x1 - x0), Vec3::Zero()};
  }
  const Vec3 x0 = x0Of(q, n), x1 = x0Of(q, n + 1), x2 = x0Of(q, n + 2);
  return {x1, 0.5 * (x2 - x0), 0.5 * (x0 + x2) - x1};
}

// The Bernstein control points of x(z) on [-1, 1]: a - b + c, a - c, a + b + c. Their convex
// hull, hence their box, contains the element's centreline.
inline BoxD controlPointBox(const CentrelinePolynomial& P) {
  const Vec3 p0 = P.a - P.b + P.c, p1 = P.a - P.c, p2 = P.a + P.b + P.c;
  return {p0.cwiseMin(p1).cwiseMin(p2), p0.cwiseMax(p1).cwiseMax(p2)};
}

struct CentrelinePoint {
  Vec3 x;     // x0(s), mm
  Vec3 dxds;  // dx0/ds, -
};

inline CentrelinePoint centrelineAt(const FibreStore& fs, const CentrelineStore& cl, Index f,
                                    double s) {
  const FibrePoint fp = locate(fs, f, s);
  const CentrelinePolynomial& P = cl.poly[fp.element];
  const double z = fp.z;
  return {P.a + z * (P.b + z * P.c), (P.b + 2 * z * P.c) * (2 / elementLength(fs, f))};
}

// The section at a fibre point (as sectionAt of systems/interpolation.h, with flat loops over
// the nodal values): x0 (mm), dx0/ds, g1, g2.
inline Section sectionOf(const FibreStore& fs, const Eigen::VectorXd& q, FibrePoint p) {
  const Index f = fs.elementFibre[p.element];
  const int order = fs.order[f];
  double N[3], dN[3];
  lagrangeShape(order, p.z, N, dN);
  const double dzds = 2 * fs.elementCount[f] / fs.length[f];
  const double* x = q.data() + kNodeDofs * std::size_t(fs.elementFirstNode[p.element]);
  double v[12] = {};  // x0, dx0/ds, g1, g2
  for (int a = 0; a <= order; ++a, x += kNodeDofs)
    for (int k = 0; k < 3; ++k) {
      v[k] += N[a] * x[k];
      v[3 + k] += dN[a] * dzds * x[k];
      v[6 + k] += N[a] * x[3 + k];
      v[9 + k] += N[a] * x[6 + k];
    }
  return {Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), Vec3(v[6], v[7], v[8]),
          Vec3(v[9], v[10], v[11])};
}

// The centreline is only C0 at the nodes: within 1e-9 h of an interior element end, dx0/ds is
// taken as the mean of the two elements' one-sided derivatives (else the element's own), so
// that a point at a node has one tangent whichever element locates it.
constexpr double kNodeSnap = 1e-9;  // relative to h

// Element ends of fibre f within kNodeSnap h of s: the node index i (0 < i < n), else -1.
inline Index interiorNodeAt(const FibreStore& fs, Index f, double s) {
  const double t = s * fs.elementCount[f] / fs.length[f], i = std::round(t);
  return std::abs(t - i) <= kNodeSnap && i > 0 && i < fs.elementCount[f] ? Index(i) : -1;
}

// dx0/ds of fibre f at s (node rule above), from the element polynomials.
inline Vec3 centrelineTangent(const FibreStore& fs, const CentrelineStore& cl, Index f, double s) {
  const double dzds = 2 * fs.elementCount[f] / fs.length[f];
  const Index node = interiorNodeAt(fs, f, s);
  if (node < 0) {
    const FibrePoint fp = locate(fs, f, s);
    const CentrelinePolynomial& P = cl.poly[fp.element];
    return (P.b + 2 * fp.z * P.c) * dzds;
  }
  const CentrelinePolynomial &L = cl.poly[fs.firstElement[f] + node - 1],
                             &R = cl.poly[fs.firstElement[f] + node];
  return 0.5 * dzds * ((L.b + 2 * L.c) + (R.b - 2 * R.c));
}

// d2x0/ds2 of fibre f at s: twice the element polynomial's c, times (dz/ds)^2 (1/mm).
inline Vec3 centrelineSecond(const FibreStore& fs, const CentrelineStore& cl, Index f, double s) {
  const double dzds = 2 / elementLength(fs, f);
  return 2 * cl.poly[locate(fs, f, s).element].c * (dzds * dzds);
}

// The section of fibre f at s from the nodes of q (sectionOf), dx0/ds by the node rule above.
inline Section contactSection(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s) {
  const Index node = interiorNodeAt(fs, f, s);
  if (node < 0) return sectionOf(fs, q, locate(fs, f, s));
  const Index e = fs.firstElement[f] + node;
  Section sec = sectionOf(fs, q, {e, -1.0});
  sec.dx0ds = 0.5 * (sec.dx0ds + sectionOf(fs, q, {e - 1, 1.0}).dx0ds);
  return sec;
}

struct ClosestPoint {
  double z;      // element parameter of the closest point
  double dist2;  // squared distance, mm^2
};

// Closest point of x(z) = a + b z + c z^2, z in [z0, z1], to p: the global minimum of
// D(z) = |x(z) - p|^2, a quartic. Its half-derivative g = (x - p).x' is a cubic whose
// derivative g' = |x'|^2 + (x - p).x'' is quadratic: the roots of g' split [z0, z1] into pieces
// where g is monotone; a piece where g rises through 0 holds one local minimum, found by Newton
// safeguarded by bisection. The minimum over those and the end points wins (ties: smaller z).
ClosestPoint closestOnPolynomial(const CentrelinePolynomial& P, const Vec3& p, double z0,
                                 double z1);

// Closest point of fibre f's centreline, restricted to s in [sa, sb], to p. Returns s (mm) and
// the squared distance (ties: smaller s).
struct ClosestOnFibre {
  double s, dist2;
};
ClosestOnFibre closestOnFibre(const FibreStore& fs, const CentrelineStore& cl, Index f,
                              const Vec3& p, double sa, double sb);

// Eq. 8 on fibre f: s in [sa, sb] with (x0(s) - xInt) . t = 0, t unit. Newton from s0 (c0 its
// centreline point) while it stays in [sa, sb]; otherwise the sign change of f nearest s0 among
// samples every h / 2 is bisected. Returns false (s untouched) when the plane cut is ill-posed:
// the fibre makes more than 80 deg with t at s0 (the plane nearly contains it), or f has no
// sign change in [sa, sb].
constexpr double kPlaneCutMinCosine = 0.17364817766693033;  // cos 80 deg
bool planeCut(const FibreStore& fs, const CentrelineStore& cl, Index f, const Vec3& xInt,
              const Vec3& t, double s0, const CentrelinePoint& c0, double sa, double sb,
              double& s);

// Section coordinates of the particle of the deformed outline x0 + xi1 g1 + xi2 g2, |xi| = R,
// in the direction of `dir` projected onto the section plane span(g1, g2) (paper Fig. 4):
// with G = [g1 g2], the projection is G m, m = (G^T G)^-1 G^T dir, and the ray x0 + t G m meets
// the outline at xi = R m / |m|. Returns false (xi untouched) when dir has no component in the
// plane (|G m| <= 1e-9 |dir|) or the section is crushed (g1, g2 parallel).
bool outlinePoint(const Vec3& g1, const Vec3& g2, double R, const Vec3& dir, double xi[2]);

// End faces: a fibre is a cylinder cut flat at its end sections. When the section S of fibre f
// at s (mm) is one of its ends and the point c (mm) lies beyond that end's plane (by more than
// 1e-9 R), xi (section coordinates, mm) receives the point of the end
// face closest to c: the projection G m of c - x0 onto the section plane,
// m = (G^T G)^-1 G^T (c - x0), kept within the rim (|m| <= R). False (xi untouched) otherwise.
bool endFaceParticle(const FibreStore& fs, Index f, double s, const Section& S, const Vec3& c,
                     double R, double xi[2]);

// The point of section S's disc |xi| <= R (x = x0 + G xi, G = [g1 g2]; R, xi in mm) nearest the
// line through c (mm) along the unit t: the minimum of the convex quadratic
//   Q(xi) = |P (x0 - c + G xi)|^2,  P = I - t t^T,  A = G^T P G = l1 v1 v1^T + l2 v2 v2^T,
// over the disc. When l2 <= kFlatDisc l1 (the line parallel to the disc) Q depends on v1 . xi
// alone: that value, and along v2 the point nearest m (m: the tie-break, in the disc). Else the
// stationary point A^-1 b (b = -G^T P (x0 - c)) inside the disc, or the rim point where
// (A + mu I) xi = b, mu > 0 (a convex quadratic's minimum on a disc; |xi(mu)| falls with mu),
// mu by bisection. A line along the disc's normal (A = 0): m. With t = 0 (P = I), the disc
// point nearest the point c.
constexpr double kFlatDisc = 1e-6;
Eigen::Vector2d discPointNearestLine(const Section& S, double R, const Vec3& c, const Vec3& t,
                                     const Eigen::Vector2d& m);

// An end face of fibre f (section S at s, an end; radius R) against fibre o (section O at so):
// the face point deepest in o and o's section at that point's closest centreline point, jointly.
// When endFaceParticle holds for O's centre, from that particle: the least distance
//   D(xi) = min_s |x0 + G xi - x0o(s)|,  |xi| <= R,  s in [so - h_o - 2R, so + h_o + 2R]
// (clipped to o; for f == o, also kept sep (mm) from s on so's side), by descent steps that
// each take the better of two candidates when it lowers D: the disc point nearest the tangent
// line of o at the current closest point (discPointNearestLine: exact for a straight o, ties
// towards the current point), and the disc point nearest that centreline point (an exact
// block-coordinate step of D, which also descends where o curves or kinks at a node). The
// projection alone put a tilted face's particle in its middle, not at the rim point that sinks
// in first; the tangent line alone of a fixed section read a square end above an arc of radius
// 5 R as in contact. Out: xi (section coordinates, mm), so (mm) and O (its section at so, from
// q); where the deepest point lies less than `clearance` (mm) from o's axis, endFaceParticle's
// xi and the given so, O instead (an element's normal runs from o's axis through its face point,
// a direction lost as the two meet: elements pass R_o / 2, kFaceClearance; a depth alone, 0).
// False (nothing changed) when endFaceParticle does not hold. Centreline from cl, sections
// from q (one state).
constexpr double kFaceClearance = 0.5;  // of the other fibre's radius
bool endFaceContact(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                    Index f, double s, const Section& S, Index o, double sep, double clearance,
                    double& so, Section& O, double xi[2]);

// Whether the centreline of fibre f is kinked at its interior node k (1 .. n - 1): the tangents
// of the two elements that meet there, from the polynomials (dx0/dz = b -+ 2c at z = +-1),
// differ by more than `angle` (rad; the callers pass theta_parallel). A kink is a node that
// the Newton searches on smooth pieces do not land on (systems/contact_normals.h, forEachKink,
// does the same from q).
inline bool kinkedNode(const FibreStore& fs, const CentrelineStore& cl, Index f, Index k,
                       double angle) {
  const CentrelinePolynomial& A = cl.poly[fs.firstElement[f] + k - 1];
  const CentrelinePolynomial& B = cl.poly[fs.firstElement[f] + k];
  const Vec3 a = A.b + 2 * A.c, b = B.b - 2 * B.c;
  return std::atan2(a.cross(b).norm(), a.dot(b)) > angle;
}

// The point of fibre g's centreline closest to x within [lo, hi] (mm of arc length): on each
// element the window meets, Newton on (x0(z) - x) . dx0/dz = 0, clamped to the
// element's part of the window, so that a minimum at a node (a kink, or the window's end) is
// found as a clamped end; the nearest over the elements. Newton starts from the nearest of 17
// points of each element's part (the squared distance to a quadratic piece is a quartic with up
// to two minima). s receives it (unchanged when the window meets no element).
inline void closestPointOnFibre(const FibreStore& fs, const CentrelineStore& cl, Index g,
                                const Vec3& x, double lo, double hi, double& s) {
  const double h = elementLength(fs, g);
  const Index n = fs.elementCount[g];
  double best = HUGE_VAL;
  for (Index i = std::max<Index>(0, Index(std::floor(lo / h))); i < n && i * h <= hi; ++i) {
    const CentrelinePolynomial& P = cl.poly[fs.firstElement[g] + i];
    const double zLo = std::max(-1.0, 2 * (lo - i * h) / h - 1);
    const double zHi = std::min(1.0, 2 * (hi - i * h) / h - 1);
    if (!(zLo <= zHi)) continue;
    const auto dist2 = [&](double u) { return (P.a + u * (P.b + u * P.c) - x).squaredNorm(); };
    double z = zLo;  // Newton from the nearest of 17 points of the element's part
    for (int k = 1; k <= 16; ++k) {
      const double u = zLo + (zHi - zLo) * k / 16;
      if (dist2(u) < dist2(z)) z = u;
    }
    for (int it = 0; it < 20; ++it) {
      const Vec3 d = P.a + z * (P.b + z * P.c) - x, t = P.b + 2 * z * P.c;
      const double slope = t.dot(t) + 2 * d.dot(P.c);
      const double next = std::clamp(slope > 0 ? z - d.dot(t) / slope : (d.dot(t) > 0 ? zLo : zHi),
                                     zLo, zHi);
      const bool done = std::abs(next - z) <= 1e-12;
      z = next;
      if (done) break;
    }
    if (dist2(z) < best) best = dist2(z), s = (i + 0.5 * (z + 1)) * h;
  }
}

}  // namespace fibra
