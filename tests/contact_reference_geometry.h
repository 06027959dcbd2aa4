// Geometric primitives of the brute-force contact reference (tests/contact_reference.h), for
// tests only, written independently of systems/: sections by interpolation.h's sectionAt,
// closest points by dense sampling and bisection, plane cuts by sampling, particles by least
// squares, the end-face rule's deepest point by a polar grid and a compass search, and the
// closest points of two tangent-line segments by coordinate descent.
#pragma once

#include "components/contact.h"
#include "systems/interpolation.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibra::reference {

// The section at s; within 1e-9 h of an interior node, the tangent is the mean of both sides'.
inline Section at(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s) {
  const double h = fs.length[f] / fs.elementCount[f], node = std::round(s / h);
  Section c = sectionAt(fs, q, locate(fs, f, s));
  if (std::abs(s / h - node) <= 1e-9 && node > 0 && node < fs.elementCount[f]) {
    const Index e = fs.firstElement[f] + Index(node);
    c.dx0ds = 0.5 * (sectionAt(fs, q, {e - 1, 1.0}).dx0ds + sectionAt(fs, q, {e, -1.0}).dx0ds);
  }
  return c;
}

// Closest point of fibre f restricted to [sa, sb] to p: 64 samples per element length, then
// bisection of g(s) = (x(s) - p).x'(s) around every sampled local minimum. Returns distance.
inline double closest(const FibreStore& fs, const Eigen::VectorXd& q, Index f, const Vec3& p,
                      double sa, double sb, double& sOut) {
  const double h = fs.length[f] / fs.elementCount[f];
  const int n = std::max(64, int(std::ceil((sb - sa) / h * 64)));
  std::vector<double> s(n + 1), D(n + 1);
  for (int i = 0; i <= n; ++i) {
    s[i] = i == n ? sb : sa + (sb - sa) * i / n;
    D[i] = (at(fs, q, f, s[i]).x0 - p).squaredNorm();
  }
  auto g = [&](double u) {
    const Section c = at(fs, q, f, u);
    return (c.x0 - p).dot(c.dx0ds);
  };
  double best = 1e300;
  sOut = sa;
  for (int i = 0; i <= n; ++i) {
    if ((i > 0 && D[i - 1] < D[i]) || (i < n && D[i + 1] < D[i])) continue;
    double lo = s[std::max(i - 1, 0)], hi = s[std::min(i + 1, n)], u = s[i];
    if (g(lo) < 0 && g(hi) > 0) {
      for (int it = 0; it < 80; ++it) {
        u = 0.5 * (lo + hi);
        (g(u) < 0 ? lo : hi) = u;
      }
    }
    const double d = (at(fs, q, f, u).x0 - p).squaredNorm();
    if (d < best || (d == best && u < sOut)) best = d, sOut = u;
  }
  return std::sqrt(best);
}

// Every root of (x(s) - xInt).t in [sa, sb]: sign changes over 400 samples, then bisection.
inline std::vector<double> planeRoots(const FibreStore& fs, const Eigen::VectorXd& q, Index f,
                                      const Vec3& xInt, const Vec3& t, double sa, double sb) {
  auto F = [&](double u) { return (at(fs, q, f, u).x0 - xInt).dot(t); };
  std::vector<double> roots;
  const int n = 400;
  double u0 = sa, f0 = F(sa);
  for (int i = 1; i <= n; ++i) {
    const double u1 = sa + (sb - sa) * i / n, f1 = F(u1);
    if (f0 == 0) roots.push_back(u0);
    else if ((f0 < 0) != (f1 < 0) && f1 != 0) {
      double lo = u0, hi = u1;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        ((F(mid) < 0) == (f0 < 0) ? lo : hi) = mid;
      }
      roots.push_back(0.5 * (lo + hi));
    }
    u0 = u1, f0 = f1;
  }
  if (f0 == 0) roots.push_back(sb);
  return roots;
}

// Particle on the outline towards the projection of dir onto span(g1, g2), by least squares.
inline bool particle(const Section& c, double R, const Vec3& dir, double xi[2]) {
  const Vec3 n = c.g1.cross(c.g2).normalized();
  const Vec3 inPlane = dir - dir.dot(n) * n;
  if (!(inPlane.norm() > 1e-9 * dir.norm())) return false;
  Eigen::Matrix<double, 3, 2> G;
  G << c.g1, c.g2;
  const Eigen::Vector2d m = G.colPivHouseholderQr().solve(inPlane);
  xi[0] = R * m(0) / m.norm();
  xi[1] = R * m(1) / m.norm();
  return true;
}

inline Vec3 facePoint(const Section& c, const double xi[2]) {
  return c.x0 + xi[0] * c.g1 + xi[1] * c.g2;
}

// What endFace found beside the particle: the deepest point is not unique (a tie: only the
// element's gap is compared), or its foot lies at a kink (ambiguous: nothing compared).
struct FaceSearch {
  bool tie = false, ambiguous = false;
};

// End faces: a section at an end of its fibre whose partner's centre lies beyond the end
// plane takes its particle on the flat face, at the face point deepest in the partner: the
// least distance from the disc |xi| <= R to the partner's centreline within h + 2 R of the
// paired section (kept the separation away from the end for self-contact), by a polar grid
// of 24 x 144 points (closest() for each) and a compass search from its best point; the
// partner's section moves to that point's closest centreline point, and its particle faces
// the face point; N is normal to the partner's axis there. Where the distance changes by
// less than 1e-12 mm across 1e-3 R about that point (a face parallel to a straight partner:
// a chord of equal depth), the element's particles are a tie, and only its gap is compared.
// Where that point lies within half the partner's radius of its axis, the direction from
// the axis is ill-posed: the face particle is the projection of the partner's centre onto
// the face (within the rim) and the partner keeps its section.
// f's section c at s, o's section `other` at so (in: the pairing; out: the foot), sep the
// self-contact separation (mm); false when c is no end of f or o's centre is not beyond it.
inline bool endFace(const FibreStore& fs, const Eigen::VectorXd& q, double sep, Index f, double s,
                    const Section& c, Index o, double& so, Section& other, double xi[2],
                    FaceSearch& r) {
  const double L = fs.length[f], R = fs.radius[f];
  const double out = s <= 1e-9 * L ? -1.0 : s >= L - 1e-9 * L ? 1.0 : 0.0;
  if (out == 0 || (other.x0 - c.x0).dot(out * c.dx0ds.normalized()) <= 1e-9 * R) return false;
  const double reach = fs.length[o] / fs.elementCount[o] + 2 * R;
  double a = std::max(0.0, so - reach), b = std::min(fs.length[o], so + reach);
  if (f == o) {
    if (so < s) b = std::min(b, s - sep);
    else a = std::max(a, s + sep);
  }
  const auto projection = [&] {
    Eigen::Matrix<double, 3, 2> G;
    G << c.g1, c.g2;
    Eigen::Vector2d m = G.colPivHouseholderQr().solve(other.x0 - c.x0);
    if (m.norm() > R) m *= R / m.norm();
    xi[0] = m(0), xi[1] = m(1);
    return true;
  };
  if (!(a < b)) return projection();  // no window
  const auto dist = [&](const Eigen::Vector2d& m, double& sOut) {
    const double x[2] = {m(0), m(1)};
    return closest(fs, q, o, facePoint(c, x), a, b, sOut);
  };
  const auto inDisc = [&](Eigen::Vector2d m) {
    return m.norm() > R ? Eigen::Vector2d(m * (R / m.norm())) : m;
  };
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  double sBest = 0, dBest = dist(best, sBest);
  for (int i = 1; i <= 24; ++i)
    for (int j = 0; j < 144; ++j) {
      const double r = R * i / 24, phi = 2 * 3.14159265358979323846 * j / 144;
      const Eigen::Vector2d m(r * std::cos(phi), r * std::sin(phi));
      double sm;
      if (const double d = dist(m, sm); d < dBest) dBest = d, best = m, sBest = sm;
    }
  for (double step = R / 24; step > 1e-13 * R;) {
    bool moved = false;
    for (const Eigen::Vector2d& dir : {Eigen::Vector2d(1, 0), Eigen::Vector2d(-1, 0),
                                      Eigen::Vector2d(0, 1), Eigen::Vector2d(0, -1)}) {
      const Eigen::Vector2d m = inDisc(best + step * dir);
      double sm;
      if (const double d = dist(m, sm); d < dBest) {
        dBest = d, best = m, sBest = sm, moved = true;
        break;
      }
    }
    if (!moved) step *= 0.5;
  }
  // the least change of the distance over 1e-3 R about the point, in four directions
  double least = 1e300, sm;
  const Eigen::Vector2d dirs[4] = {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1),
                                   Eigen::Vector2d(1, 1).normalized(),
                                   Eigen::Vector2d(1, -1).normalized()};
  for (const Eigen::Vector2d& dir : dirs) {
    const Eigen::Vector2d up = inDisc(best + 1e-3 * R * dir), down = inDisc(best - 1e-3 * R * dir);
    least = std::min(least, std::max(std::abs(dist(up, sm) - dBest) * ((up - best).norm() > 0),
                                     std::abs(dist(down, sm) - dBest) * ((down - best).norm() > 0)));
  }
  // a closest point at the window's end is no foot of a perpendicular: the distance has a kink
  // there, where the compass search and the pipeline's descent may stop apart
  r.tie = least < 1e-12 || sBest <= a + 1e-9 || sBest >= b - 1e-9;
  // the partner's axis reached (within half its radius): the projection, the paired section
  if (dBest < 0.5 * fs.radius[o]) {
    r.tie = false;
    return projection();
  }
  // a foot at an interior node, where a deformed centreline kinks: the tangent there (either
  // side's, or their mean within 1e-9 h) and with it N is a matter of round-off
  const double h = fs.length[o] / fs.elementCount[o], node = std::round(sBest / h);
  if (node > 0 && node < fs.elementCount[o] && std::abs(sBest / h - node) <= 1e-6)
    r.ambiguous = true;
  xi[0] = best(0), xi[1] = best(1);
  so = sBest;
  other = at(fs, q, o, so);
  return true;
}

// The room of a section at s of fibre f towards its fibre's ends or kinks (mm), each beyond
// 2 (R_I + R_J) not counted: a kink is an interior node where the two elements' tangents at the
// state q differ by more than `kinkAngle` (rad); a section at such a node has none on either
// side, else a kink counts before it when its node starts or precedes the section's element.
inline void sectionRoom(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s,
                        double reach, double kinkAngle, double& lo, double& hi) {
  const auto cap = [reach](double room) { return room <= reach ? room : 1e300; };
  double before = s, after = fs.length[f] - s;
  const double h = fs.length[f] / double(fs.elementCount[f]);
  const Index own = locate(fs, f, s).element - fs.firstElement[f];
  for (Index k = 1; k < fs.elementCount[f]; ++k) {
    const double sk = double(k) * h;
    if (std::abs(sk - s) > reach) continue;
    const Vec3 a = sectionAt(fs, q, {fs.firstElement[f] + k - 1, 1.0}).dx0ds.normalized();
    const Vec3 b = sectionAt(fs, q, {fs.firstElement[f] + k, -1.0}).dx0ds.normalized();
    if (!(std::acos(std::clamp(a.dot(b), -1.0, 1.0)) > kinkAngle)) continue;
    if (std::abs(s / h - double(k)) <= 1e-9) before = after = 0;
    else if (k <= own) before = std::min(before, s - sk);
    else after = std::min(after, sk - s);
  }
  lo = -cap(before), hi = cap(after);
}

// The eq. 10 crossing normal past an end or a kink: where the closest points of the tangent lines
// x0I + lambda t_I, x0J + mu t_J lie past a fibre's end or kink (lambda within the room
// sectionRoom gives the section, mu likewise), `offset` receives the vector between
// the closest points of the two segments, the convex quadratic |x0I - x0J + lambda t_I - mu t_J|^2
// minimised on that box by exact coordinate steps, each clamped, until neither moves by 1e-15 mm;
// true then, false (offset untouched) where the lines' closest points lie within both.
inline bool segmentOffset(const FibreStore& fs, const Eigen::VectorXd& q, double kinkAngle,
                          Index I, double sIs, const Section& sI, Index J, double sJs,
                          const Section& sJ, Vec3& offset) {
  const Vec3 tI = sI.dx0ds.normalized(), tJ = sJ.dx0ds.normalized();
  Eigen::Matrix<double, 3, 2> A;
  A << tI, -tJ;
  const Vec3 r = sI.x0 - sJ.x0;
  Eigen::Vector2d lm = A.colPivHouseholderQr().solve(Vec3(-r));
  const double reach = 2 * (fs.radius[I] + fs.radius[J]);
  double loI, hiI, loJ, hiJ;
  sectionRoom(fs, q, I, sIs, reach, kinkAngle, loI, hiI);
  sectionRoom(fs, q, J, sJs, reach, kinkAngle, loJ, hiJ);
  if (!(lm(0) < loI || lm(0) > hiI || lm(1) < loJ || lm(1) > hiJ)) return false;
  lm = Eigen::Vector2d(std::clamp(lm(0), loI, hiI), std::clamp(lm(1), loJ, hiJ));
  for (int it = 0; it < 100000; ++it) {
    const double l = std::clamp(lm(1) * tI.dot(tJ) - tI.dot(r), loI, hiI);
    const double m = std::clamp(l * tI.dot(tJ) + tJ.dot(r), loJ, hiJ);
    const bool still = std::abs(l - lm(0)) + std::abs(m - lm(1)) <= 1e-15;
    lm = Eigen::Vector2d(l, m);
    if (still) break;
  }
  offset = r + lm(0) * tI - lm(1) * tJ;
  return true;
}

}  // namespace fibra::reference
