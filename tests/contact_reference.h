// Brute-force reference of the contact detection, for tests only. Written independently of
// systems/: O(F^2) fibre pairs with no broadphase, every test point of every pair, the closest
// point over every element of J by dense sampling and bisection, the centreline from
// interpolation.h's sectionAt (not the per-element polynomials), L_int as a fine chord sum,
// plane cuts by sampling and bisection, the closest points of a crossing by Newton on a
// difference Hessian, particles by a least-squares solve, normals from acos.
// It shares with the pipeline only the definitions: ContactParams (Delta_prox, the test-point
// spacing rule, the angles, the self-contact separation) and the documented fallback rules.
#pragma once

#include "components/contact.h"
#include "engine/contact_setup.h"
#include "systems/contact_params.h"
#include "systems/interpolation.h"
#include "contact_reference_geometry.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace fibra::reference {

struct Zone {
  Index I, J;
  double sI1, sI2, sJ1, sJ2, minDistance;
  Index testPoints;
};

struct Element {
  double zeta, length;  // abscissa on the intermediate geometry, share of it (mm)
  double sI, sJ, xiI[2], xiJ[2];
  Vec3 normal;
  double gap, theta;
  std::uint8_t fallback;  // section and tangent bits only (kFallbackSectionI/J, kFallbackTangent)
  bool ambiguous;         // several plane-cut roots: the pipeline's choice is not checked
  bool dip = false;       // one of a point zone's m >= 2 minima (length L_int / m)
  bool faceTie = false;   // an end face's deepest point is not unique: only the gap is compared
  bool pastEnd = false;   // the crossing normal from the segments' closest points (past an end)
};

struct Detection {
  std::vector<Zone> zones;
  int ambiguousPoints = 0;  // test points within 1e-9 mm of Delta_prox
};


inline Detection detect(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p) {
  Detection out;
  for (Index I = 0; I < fs.fibres(); ++I)
    for (Index J = I; J < fs.fibres(); ++J) {
      if (I == J && !p.selfContact) continue;
      const int m = testIntervalsPerElement(fs, p, I, J);
      const double l = fs.length[I] / fs.elementCount[I] / m;
      const double delta = proximityDistance(p, I, J);
      bool open = false;
      Zone z{};
      for (std::int64_t k = 0; k <= std::int64_t(fs.elementCount[I]) * m; ++k) {
        const double s = double(k) * l;
        const Vec3 x = at(fs, q, I, s).x0;
        double sJ = 0, d = 1e300;
        const double sa = I == J ? s + p.selfSeparation[I] : 0;
        if (sa <= fs.length[J]) d = closest(fs, q, J, x, sa, fs.length[J], sJ);
        if (std::abs(d - delta) < 1e-9) ++out.ambiguousPoints;
        if (d <= delta) {
          if (!open) z = {I, J, s, s, sJ, sJ, d, 0};
          open = true;
          z.sI2 = s, z.sJ2 = sJ, z.minDistance = std::min(z.minDistance, d), ++z.testPoints;
        } else if (open) {
          out.zones.push_back(z);
          open = false;
        }
      }
      if (open) out.zones.push_back(z);
    }
  return out;
}


// The contact elements of one zone (eqs. 5-11 and the documented fallbacks); `ambiguousCount`
// is set when 2 L_int / h_min lies within 1e-6 of a whole number (Nc not checked).
inline std::vector<Element> elements(const FibreStore& fs, const Eigen::VectorXd& q,
                                     const ContactParams& p, const Zone& z, bool& ambiguousCount) {
  const Index I = z.I, J = z.J;
  const double dI = z.sI2 - z.sI1, dJ = z.sJ2 - z.sJ1, delta = proximityDistance(p, I, J);
  auto xInt = [&](double zeta) {
    return Vec3(0.5 * (at(fs, q, I, (1 - zeta) * z.sI1 + zeta * z.sI2).x0 +
                       at(fs, q, J, (1 - zeta) * z.sJ1 + zeta * z.sJ2).x0));
  };
  // L_int: chord sums between the kinks (the zeta of every node of I and J), with 64 and 128
  // chords per piece, Richardson-extrapolated (x_int is smooth within a piece).
  std::vector<double> breaks{0, 1};
  for (auto [f, s1, d] : {std::tuple{I, z.sI1, dI}, std::tuple{J, z.sJ1, dJ}}) {
    const double h = fs.length[f] / fs.elementCount[f];
    for (Index n = 1; n < fs.elementCount[f] && d != 0; ++n)
      if (const double zeta = (n * h - s1) / d; zeta > 0 && zeta < 1) breaks.push_back(zeta);
  }
  std::sort(breaks.begin(), breaks.end());
  double L = 0;
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    auto chordSum = [&](int n) {
      double sum = 0;
      for (int i = 0; i < n; ++i) {
        const double u0 = breaks[b] + (breaks[b + 1] - breaks[b]) * i / n;
        const double u1 = breaks[b] + (breaks[b + 1] - breaks[b]) * (i + 1) / n;
        sum += (xInt(u1) - xInt(u0)).norm();
      }
      return sum;
    };
    L += (4 * chordSum(128) - chordSum(64)) / 3;
  }
  const double hMin = std::min(fs.length[I] / fs.elementCount[I], fs.length[J] / fs.elementCount[J]);
  const double ratio = 2 * L / hMin;
  ambiguousCount = std::floor(ratio * (1 - 1e-6)) < 2 && std::floor(ratio * (1 + 1e-6)) >= 2;
  // Placement (docs/CONTACT.md 1.4): a point contact, one element at 1/2 carrying L; else the
  // zone cut at the element ends of I and J, a cut within h_min / 10 (of arc length on the
  // fibre with the longer interval) of the last kept cut or of the zone's end dropped, two Gauss
  // points per piece.
  std::vector<std::pair<double, double>> placed;  // (zeta, length)
  if (std::floor(ratio) < 2) {
    placed.push_back({0.5, L});
  } else {
    const double span = std::max(std::abs(dI), std::abs(dJ));
    auto tInt = [&](double zeta) {
      return Vec3(0.5 * (at(fs, q, I, (1 - zeta) * z.sI1 + zeta * z.sI2).dx0ds * dI +
                         at(fs, q, J, (1 - zeta) * z.sJ1 + zeta * z.sJ2).dx0ds * dJ));
    };
    // The cut of an element end x_f(s): where x_int crosses the plane through it normal to
    // t_int at the linear map's guess with f's node tangent (the mean of both sides'), within
    // `window` of the guess (clamped to [0, 1]): every sign change (256 steps, bisected), the
    // one nearest the guess; the guess when there is none. Ambiguous when the pipeline's coarser
    // scan (8 steps) might pick another: a second sign change within 2 of its steps of the
    // chosen one, or not farther than one of its steps more from the guess.
    auto cutAt = [&](Index f, double s, double guess, double window) {
      const Vec3 x = at(fs, q, f, s).x0;
      const Index other = f == I ? J : I;
      const double dF = f == I ? dI : dJ, dO = f == I ? dJ : dI;
      const double sO = f == I ? (1 - guess) * z.sJ1 + guess * z.sJ2 : (1 - guess) * z.sI1 + guess * z.sI2;
      const Vec3 tHat = 0.5 * (at(fs, q, f, s).dx0ds * dF + at(fs, q, other, sO).dx0ds * dO);
      auto F = [&](double u) { return (xInt(u) - x).dot(tHat); };
      const double lo = std::max(0.0, guess - window), hi = std::min(1.0, guess + window);
      const double coarse = (hi - lo) / 8;
      std::vector<double> roots;
      for (int i = 0; i < 256; ++i) {
        double a = lo + (hi - lo) * i / 256.0, b = lo + (hi - lo) * (i + 1) / 256.0, fa = F(a);
        if ((fa > 0) == (F(b) > 0)) continue;
        for (int k = 0; k < 60; ++k) {
          const double m = 0.5 * (a + b);
          if ((F(m) > 0) == (fa > 0)) a = m; else b = m;
        }
        roots.push_back(a);
      }
      if (roots.empty()) return guess;
      std::sort(roots.begin(), roots.end(),
                [&](double u, double v) { return std::abs(u - guess) < std::abs(v - guess); });
      for (std::size_t k = 1; k < roots.size(); ++k)
        if (std::abs(roots[k] - roots[0]) < 2 * coarse ||
            std::abs(roots[k] - guess) - std::abs(roots[0] - guess) < coarse)
          ambiguousCount = true;
      return roots[0];
    };
    std::vector<double> all;
    for (auto [f, s1, d] : {std::tuple{I, z.sI1, dI}, std::tuple{J, z.sJ1, dJ}}) {
      const double h = fs.length[f] / fs.elementCount[f];
      for (Index n = 1; n < fs.elementCount[f] && d != 0; ++n)
        if (const double zeta = (n * h - s1) / d; zeta > 0 && zeta < 1)
          all.push_back(cutAt(f, n * h, zeta, h / std::abs(d)));
    }
    std::sort(all.begin(), all.end());
    std::vector<double> cuts{0};
    for (const double c : all) {
      const double fromLast = (c - cuts.back()) * span / hMin, toEnd = (1 - c) * span / hMin;
      if (std::abs(fromLast - 0.1) < 1e-9 || std::abs(toEnd - 0.1) < 1e-9) ambiguousCount = true;
      if (fromLast >= 0.1 && toEnd >= 0.1) cuts.push_back(c);
    }
    cuts.push_back(1);
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double a = cuts[c], b = cuts[c + 1];
      for (const double g : {-1.0, 1.0}) {
        const double zeta = 0.5 * (a + b) + g * (b - a) / (2 * std::sqrt(3.0));
        placed.push_back({zeta, 0.5 * (b - a) * tInt(zeta).norm()});
      }
    }
  }
  // The local minimum of the centreline distance D(a, b) = |x_I(a) - x_J(b)|^2 / 2 from (a, b),
  // by Newton with D's gradient [d . t_I, -d . t_J] from the sections and its Hessian by central
  // differences of the gradient; kept (a, b moved, true) when it converges inside both brackets
  // (the zone's intervals widened by Delta_prox), with the self-contact separation, at a
  // minimum, with the fibres more than theta_parallel apart (docs/CONTACT.md 1.4, "Crossings");
  // a step past a fibre's end (a bracket bound there) holds that section at the end while the
  // gradient still points outwards, and goes on in the other;
  // `curvature` receives the smaller eigenvalue of the Hessian there.
  const auto bracketOf = [&](Index f, double s1, double s2) {
    return std::pair{std::max(0.0, std::min(s1, s2) - delta), std::min(fs.length[f], std::max(s1, s2) + delta)};
  };
  const double sepIJ = I == J ? p.selfSeparation[I] : 0;
  const auto closestPair = [&](double& sa, double& sb, double& curvature) {
    const auto [aI, bI] = bracketOf(I, z.sI1, z.sI2);
    const auto [aJ, bJ] = bracketOf(J, z.sJ1, z.sJ2);
    const auto gradient = [&](double a, double b) {
      const Section A = at(fs, q, I, a), B = at(fs, q, J, b);
      const Vec3 d = A.x0 - B.x0;
      return Eigen::Vector2d(d.dot(A.dx0ds), -d.dot(B.dx0ds));
    };
    const double h = std::min(fs.length[I] / fs.elementCount[I], fs.length[J] / fs.elementCount[J]);
    const double eps = 1e-6 * h;
    Eigen::Vector2d u(sa, sb);
    const double LI = fs.length[I], LJ = fs.length[J];
    int endA = 0, endB = 0;  // held at the fibre's start (-1) or end (+1): the distance falls past it
    for (int it = 0; it < 20; ++it) {
      Eigen::Matrix2d H;
      const double cI = std::clamp(u(0), eps, LI - eps), cJ = std::clamp(u(1), eps, LJ - eps);
      H.col(0) = (gradient(cI + eps, u(1)) - gradient(cI - eps, u(1))) / (2 * eps);
      H.col(1) = (gradient(u(0), cJ + eps) - gradient(u(0), cJ - eps)) / (2 * eps);
      H = 0.5 * (H + H.transpose()).eval();
      const Eigen::Vector2d gr = gradient(u(0), u(1));
      if (endA && !(endA * gr(0) < 0)) endA = 0;
      if (endB && !(endB * gr(1) < 0)) endB = 0;
      Eigen::Vector2d step = Eigen::Vector2d::Zero();
      if (endA && endB) {
      } else if (endB) {
        if (!(H(0, 0) > 0)) return false;
        step(0) = -gr(0) / H(0, 0);
      } else if (endA) {
        if (!(H(1, 1) > 0)) return false;
        step(1) = -gr(1) / H(1, 1);
      } else {
        if (!(H(0, 0) > 0 && H.determinant() > 0)) return false;
        step = -H.ldlt().solve(gr);
      }
      u += step;
      if (u(0) < aI && aI <= 0) u(0) = 0, endA = -1;
      if (u(0) > bI && bI >= LI) u(0) = LI, endA = 1;
      if (u(1) < aJ && aJ <= 0) u(1) = 0, endB = -1;
      if (u(1) > bJ && bJ >= LJ) u(1) = LJ, endB = 1;
      if (!(u(0) >= aI && u(0) <= bI && u(1) >= aJ && u(1) <= bJ)) return false;
      if (I == J && !(u(1) - u(0) >= sepIJ)) return false;  // self-contact: apart by the separation
      if (step.lpNorm<1>() <= 1e-10 * h) {
        const Vec3 uI = at(fs, q, I, u(0)).dx0ds.normalized(), uJ = at(fs, q, J, u(1)).dx0ds.normalized();
        if (uI.cross(uJ).norm() <= std::sin(p.thetaParallel)) return false;
        sa = u(0), sb = u(1);
        curvature = H.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff();
        return true;
      }
    }
    return false;
  };
  // One element at zeta: eq. 8 sections (or, with `from`, that element's sections), the
  // closest points when `closestPoints`; `curvature` receives the smaller eigenvalue of the
  // distance's Hessian there (0 when Newton did not keep them).
  const auto element = [&](double zeta, double length, bool closestPoints, const Element* from,
                           double& curvature) -> Element {
    curvature = 0;
    const double sIz = (1 - zeta) * z.sI1 + zeta * z.sI2, sJz = (1 - zeta) * z.sJ1 + zeta * z.sJ2;
    const Section cI = at(fs, q, I, sIz), cJ = at(fs, q, J, sJz);
    const Vec3 x = 0.5 * (cI.x0 + cJ.x0), tInt = 0.5 * (cI.dx0ds * dI + cJ.dx0ds * dJ);
    Element e{};
    e.zeta = zeta, e.length = length;
    Vec3 t;
    if (tInt.norm() > 1e-9 * 0.5 * (std::abs(dI) + std::abs(dJ))) {
      t = tInt.normalized();
    } else {
      const Vec3 tI = cI.dx0ds.normalized(), tJ = cJ.dx0ds.normalized();
      t = (tI + (tI.dot(tJ) < 0 ? -tJ : tJ)).normalized();
      e.fallback |= kFallbackTangent;
    }
    auto cut = [&](Index f, const Section& c0, double s0, double s1, double s2, double& s) {
      if (std::abs(c0.dx0ds.dot(t)) < 0.17364817766693033 * c0.dx0ds.norm()) return false;
      const double sa = std::max(0.0, std::min(s1, s2) - delta);
      const double sb = std::min(fs.length[f], std::max(s1, s2) + delta);
      // Expect the root nearest s(zeta); ambiguous when another root is nearly as close or the
      // nearest is far (Newton's choice is then not defined by "nearest").
      std::vector<double> r = planeRoots(fs, q, f, x, t, sa, sb);
      if (r.empty()) return false;
      std::sort(r.begin(), r.end(), [&](double a, double b) { return std::abs(a - s0) < std::abs(b - s0); });
      const double h = fs.length[f] / fs.elementCount[f];
      if (r.size() > 1 && (std::abs(r[0] - s0) > 0.25 * h || std::abs(r[1] - s0) < 3 * std::abs(r[0] - s0) + 1e-3 * h))
        e.ambiguous = true;
      s = r[0];
      return true;
    };
    e.sI = sIz, e.sJ = sJz;
    const bool okI = from || cut(I, cI, sIz, z.sI1, z.sI2, e.sI);
    const bool okJ = from || cut(J, cJ, sJz, z.sJ1, z.sJ2, e.sJ);
    if (from) e.sI = from->sI, e.sJ = from->sJ, e.fallback = from->fallback & 7, e.ambiguous = from->ambiguous;
    auto bracket = [&](Index f, double s1, double s2) {
      return std::pair{std::max(0.0, std::min(s1, s2) - delta), std::min(fs.length[f], std::max(s1, s2) + delta)};
    };
    const double sep = I == J ? p.selfSeparation[I] : 0;
    if (!okI) e.fallback |= kFallbackSectionI;
    if (!okJ) e.fallback |= kFallbackSectionJ;
    if (!okI && okJ) {
      auto [a, b] = bracket(I, z.sI1, z.sI2);
      if (I == J) b = std::min(b, e.sJ - sep);
      if (a <= b) closest(fs, q, I, at(fs, q, J, e.sJ).x0, a, b, e.sI);
    } else if (!okJ) {
      auto [a, b] = bracket(J, z.sJ1, z.sJ2);
      if (I == J) a = std::max(a, e.sI + sep);
      if (a <= b) closest(fs, q, J, at(fs, q, I, e.sI).x0, a, b, e.sJ);
    }
    // Both cuts well posed: the pair moved, within the eq. 8 plane (its midpoint kept on it), to
    // the local minimum of |x_I(a) - x_J(b)|, by Newton on the Lagrangian's stationarity
    // [d . t_I + l/2 t_I . t, -d . t_J + l/2 t_J . t, c] with its (a, b) columns by central
    // differences; steps limited to h / 4; kept when it converges inside both brackets (and the
    // self-contact separation) to a minimum along the plane and brings the centres closer by more
    // than p_max / 10 (systems/contact_sections.h).
    if (okI && okJ && !from) {
      const auto [aI, bI] = bracket(I, z.sI1, z.sI2);
      const auto [aJ, bJ] = bracket(J, z.sJ1, z.sJ2);
      const double h = std::min(fs.length[I] / fs.elementCount[I], fs.length[J] / fs.elementCount[J]);
      const double eps = 1e-6 * h;
      const auto stationarity = [&](double a, double b, double l) {
        const Section A = at(fs, q, I, a), B = at(fs, q, J, b);
        const Vec3 d = A.x0 - B.x0;
        return Eigen::Vector3d(d.dot(A.dx0ds) + 0.5 * l * A.dx0ds.dot(t),
                               -d.dot(B.dx0ds) + 0.5 * l * B.dx0ds.dot(t),
                               (0.5 * (A.x0 + B.x0) - x).dot(t));
      };
      const auto distance = [&](double a, double b) { return (at(fs, q, I, a).x0 - at(fs, q, J, b).x0).norm(); };
      double a = e.sI, b = e.sJ, l = 0;
      {
        const Section A = at(fs, q, I, a), B = at(fs, q, J, b);
        const Vec3 d = A.x0 - B.x0;
        const Eigen::Vector2d gc(0.5 * A.dx0ds.dot(t), 0.5 * B.dx0ds.dot(t));
        l = -Eigen::Vector2d(d.dot(A.dx0ds), -d.dot(B.dx0ds)).dot(gc) / gc.squaredNorm();
      }
      for (int it = 0; it < 20; ++it) {
        Eigen::Matrix3d K;
        K.col(0) = (stationarity(a + eps, b, l) - stationarity(a - eps, b, l)) / (2 * eps);
        K.col(1) = (stationarity(a, b + eps, l) - stationarity(a, b - eps, l)) / (2 * eps);
        K.col(2) = Eigen::Vector3d(0.5 * at(fs, q, I, a).dx0ds.dot(t), 0.5 * at(fs, q, J, b).dx0ds.dot(t), 0);
        const Eigen::Vector2d tangent(K(2, 1), -K(2, 0));
        if (!(tangent.dot(K.topLeftCorner<2, 2>() * tangent) > 0)) break;
        Eigen::Vector3d step = -K.fullPivLu().solve(stationarity(a, b, l));
        const double size = std::max(std::abs(step(0)), std::abs(step(1)));
        if (size > 0.25 * h) step *= 0.25 * h / size;
        a += step(0), b += step(1), l += step(2);
        if (!(a >= aI && a <= bI && b >= aJ && b <= bJ) || (I == J && !(b - a >= sep))) break;
        if (size <= 1e-10 * h) {
          if (distance(a, b) < distance(e.sI, e.sJ) - 0.1 * pairPMax(p, I, J)) e.sI = a, e.sJ = b;
          break;
        }
      }
    }
    // A point element: both sections moved to the local minimum of the centreline distance
    // from there (closestPair below).
    if (closestPoints && !from) {
      double c = 0;
      if (closestPair(e.sI, e.sJ, c)) curvature = c;
    }
    const Section sI = at(fs, q, I, e.sI), sJ = at(fs, q, J, e.sJ);
    const Vec3 tI = sI.dx0ds.normalized(), tJ = sJ.dx0ds.normalized();
    Vec3 n = tI.cross(tJ);
    if (n.norm() > 1e-12) n.normalize(); else n = sI.g1.normalized();
    if (!particle(sI, fs.radius[I], sJ.x0 - sI.x0, e.xiI) && !particle(sI, fs.radius[I], -n, e.xiI))
      e.xiI[0] = -fs.radius[I], e.xiI[1] = 0;
    if (!particle(sJ, fs.radius[J], sI.x0 - sJ.x0, e.xiJ) && !particle(sJ, fs.radius[J], n, e.xiJ))
      e.xiJ[0] = fs.radius[J], e.xiJ[1] = 0;
    // End faces (endFace, tests/contact_reference_geometry.h): the face point deepest in the
    // partner, the partner's section moved to its foot; N normal to the partner's axis there.
    FaceSearch found;
    const auto face = [&](Index f, double s, const Section& c, Index o, double& so, Section& other,
                          double xi[2]) {
      return endFace(fs, q, p.selfSeparation[f], f, s, c, o, so, other, xi, found);
    };
    e.theta = std::acos(std::min(1.0, std::abs(tI.dot(tJ))));
    {
      Section cI = sI, cJ = sJ;
      int side = 0;
      if (face(I, e.sI, cI, J, e.sJ, cJ, e.xiI)) {
        side = 1;
        particle(cJ, fs.radius[J], facePoint(cI, e.xiI) - cJ.x0, e.xiJ);
      } else if (face(J, e.sJ, cJ, I, e.sI, cI, e.xiJ)) {
        side = 2;
        particle(cI, fs.radius[I], facePoint(cJ, e.xiJ) - cI.x0, e.xiI);
      }
      e.faceTie = found.tie;
      e.ambiguous = e.ambiguous || found.ambiguous;
      if (side) {
        const Vec3 fI = cI.dx0ds.normalized(), fJ = cJ.dx0ds.normalized();
        e.theta = std::acos(std::min(1.0, std::abs(fI.dot(fJ))));
        const Vec3 pI = facePoint(cI, e.xiI), pJ = facePoint(cJ, e.xiJ);
        const Vec3 axis = side == 1 ? fJ : fI, r = side == 1 ? Vec3(pI - cJ.x0) : Vec3(cI.x0 - pJ);
        e.fallback |= side == 1 ? kEndFaceI : kEndFaceJ;
        const Vec3 nf = r - r.dot(axis) * axis;
        if (nf.norm() > 1e-12 * (fs.radius[I] + fs.radius[J])) {  // else (end to end): eq. 10
          e.normal = nf.normalized();
          e.gap = (pI - pJ).dot(e.normal);
          return e;
        }
      }
    }
    // eq. 10, the crossing normal between the segments' closest points past an end
    // (segmentOffset, tests/contact_reference_geometry.h)
    const double w = std::clamp((e.theta - p.thetaParallel) / (p.thetaCross - p.thetaParallel), 0.0, 1.0);
    Vec3 segment = Vec3::Zero();
    if (w > 0) e.pastEnd = segmentOffset(fs, q, p.thetaParallel, I, e.sI, sI, J, e.sJ, sJ, segment);
    // The centre-to-centre direction without its component along the mean tangent (the
    // sections' axial offset, systems/contact_normals.h).
    const Vec3 tm = (tI + (tI.dot(tJ) < 0 ? -tJ : tJ)).normalized();
    Vec3 d = sI.x0 - sJ.x0 - (sI.x0 - sJ.x0).dot(tm) * tm;
    if (d.norm() <= 1e-9 * (fs.radius[I] + fs.radius[J])) d = sI.x0 - sJ.x0;  // end to end
    Vec3 nc = tI.cross(tJ);
    if (nc.norm() > 0) nc.normalize();
    if (nc.dot(d) < 0) nc = -nc;
    if (segment.norm() > 1e-9 * (fs.radius[I] + fs.radius[J])) nc = segment.normalized();
    e.normal = w == 1 ? nc : Vec3((w * nc + (1 - w) * d.normalized()).normalized());
    const Vec3 pI = sI.x0 + e.xiI[0] * sI.g1 + e.xiI[1] * sI.g2;
    const Vec3 pJ = sJ.x0 + e.xiJ[0] * sJ.g1 + e.xiJ[1] * sJ.g2;
    e.gap = (pI - pJ).dot(e.normal);  // eq. 11
    return e;
  };
  std::vector<Element> out;
  double curvature = 0;
  for (auto [zeta, length] : placed)
    out.push_back(element(zeta, length, placed.size() == 1, nullptr, curvature));
  // The zone's minima (docs/CONTACT.md 1.4, "Crossings in long zones" and "Every minimum of a
  // zone"): closestPair from the eq. 8 sections at zeta = 1/2 and from the linear map at
  // zeta = k / n, n = ceil(8 L_int / h_min) in [4, 256] (point zones: every k; long zones: where
  // the fibres make more than theta_parallel); distinct (|dsI| + |dsJ| > h_min / 20); kept in a
  // point zone when the centres lie within R_I + R_J + 2 p_max, in a long zone when the patch a
  // penetration p_max spans, 2 sqrt(2 (R_I + R_J) p_max / lambda_min), is shorter than h_min / 2,
  // or, held at a fibre's end, when the fibres make more than theta_cross there.
  const double pMax = p.pairs.pMax[pairClass(p, I, J)], RR = fs.radius[I] + fs.radius[J];
  const bool point = placed.size() == 1;
  const bool onI = std::abs(dI) >= std::abs(dJ);
  const auto zetaOf = [&](const Element& m) { return onI ? (m.sI - z.sI1) / dI : (m.sJ - z.sJ1) / dJ; };
  std::vector<Element> minima;
  {
    const int n = int(std::clamp(std::ceil(8 * L / hMin), 4.0, 256.0));
    std::vector<Element> starts{element(0.5, 0, false, nullptr, curvature)};
    for (int k = 0; k <= n; ++k) {
      const double zeta = double(k) / n;
      Element st{};
      st.sI = (1 - zeta) * z.sI1 + zeta * z.sI2, st.sJ = (1 - zeta) * z.sJ1 + zeta * z.sJ2;
      const Vec3 tI = at(fs, q, I, st.sI).dx0ds.normalized(), tJ = at(fs, q, J, st.sJ).dx0ds.normalized();
      if (point || tI.cross(tJ).norm() > std::sin(p.thetaParallel)) starts.push_back(st);
    }
    for (Element st : starts) {
      double lambda = 0;
      if (!closestPair(st.sI, st.sJ, lambda)) continue;
      const double d = (at(fs, q, I, st.sI).x0 - at(fs, q, J, st.sJ).x0).norm();
      const bool atEnd = st.sI <= 0 || st.sI >= fs.length[I] || st.sJ <= 0 || st.sJ >= fs.length[J];
      const double sinAngle = at(fs, q, I, st.sI).dx0ds.normalized().cross(at(fs, q, J, st.sJ).dx0ds.normalized()).norm();
      const bool keep = point   ? d < RR + 2 * pMax
                        : atEnd ? sinAngle > std::sin(p.thetaCross)
                                : lambda > 0 && 2 * std::sqrt(2 * RR * pMax / lambda) < 0.5 * hMin;
      bool known = false;
      for (const Element& m : minima) known = known || std::abs(m.sI - st.sI) + std::abs(m.sJ - st.sJ) <= hMin / 20;
      if (keep && !known) minima.push_back(st);
    }
    // Long zones: kinked vertices (an interior node where the two elements' tangents differ by
    // more than theta_parallel) in the brackets that point at the other fibre (the distance to
    // its closest point, `closest`, rising along both elements at the node).
    for (int side = 0; side < 2 && !point; ++side) {
      const Index f = side == 0 ? I : J, o = side == 0 ? J : I;
      const auto [a, b] = side == 0 ? bracketOf(I, z.sI1, z.sI2) : bracketOf(J, z.sJ1, z.sJ2);
      const auto [ao, bo] = side == 0 ? bracketOf(J, z.sJ1, z.sJ2) : bracketOf(I, z.sI1, z.sI2);
      const double h = fs.length[f] / fs.elementCount[f];
      for (Index k = 1; k < fs.elementCount[f]; ++k) {
        const double sk = double(k) * h;
        if (sk < a || sk > b) continue;
        const Section before = sectionAt(fs, q, {fs.firstElement[f] + k - 1, 1.0});
        const Section after = sectionAt(fs, q, {fs.firstElement[f] + k, -1.0});
        const double turn = std::acos(std::clamp(
            before.dx0ds.normalized().dot(after.dx0ds.normalized()), -1.0, 1.0));
        if (!(turn > p.thetaParallel)) continue;
        // the other fibre's point nearest the vertex: 1024 samples per element length, then
        // golden-section search on the distance within a sample step of the best (a kink of the
        // other fibre between two near-equal minima is in reach of neither Newton nor `closest`'s
        // bisection of its gradient)
        double so = ao;
        {
          const double ho = fs.length[o] / fs.elementCount[o];
          const int n = std::max(1024, int(std::ceil((bo - ao) / ho * 1024)));
          double best = 1e300;
          for (int i = 0; i <= n; ++i) {
            const double u = i == n ? bo : ao + (bo - ao) * i / n;
            const double dd = (at(fs, q, o, u).x0 - after.x0).squaredNorm();
            if (dd < best) best = dd, so = u;
          }
          const double step = (bo - ao) / n, g = 0.5 * (std::sqrt(5.0) - 1);
          double lo = std::max(ao, so - step), hi = std::min(bo, so + step);
          const auto dist2 = [&](double u) { return (at(fs, q, o, u).x0 - after.x0).squaredNorm(); };
          for (int it = 0; it < 120; ++it) {
            const double c = hi - g * (hi - lo), e = lo + g * (hi - lo);
            if (dist2(c) < dist2(e)) hi = e;
            else lo = c;
          }
          so = 0.5 * (lo + hi);
        }
        const Vec3 d = after.x0 - at(fs, q, o, so).x0;
        if (!(d.dot(after.dx0ds) >= 0 && d.dot(before.dx0ds) <= 0)) continue;
        Element st{};
        st.sI = side == 0 ? sk : so, st.sJ = side == 0 ? so : sk;
        if (I == J && !(std::abs(st.sJ - st.sI) >= sepIJ)) continue;
        bool known = false;
        for (const Element& m : minima) known = known || std::abs(m.sI - st.sI) + std::abs(m.sJ - st.sJ) <= hMin / 20;
        if (!known) minima.push_back(st);
      }
    }
    const bool flat = dI == 0 && dJ == 0;  // a zone of zero length: by (sI, sJ)
    std::stable_sort(minima.begin(), minima.end(), [&](const Element& a, const Element& b) {
      return flat ? a.sI < b.sI || (a.sI == b.sI && a.sJ < b.sJ) : zetaOf(a) < zetaOf(b);
    });
  }
  if (point && minima.size() == 1) {  // the zone's one element at its one touching minimum
    out[0] = element(placed[0].first, placed[0].second, false, &minima[0], curvature);
  } else if (point && minima.size() >= 2) {  // an element at each, L_int / m each
    out.clear();
    for (const Element& m : minima) {
      const double zeta = zetaOf(m);
      out.push_back(element(std::isfinite(zeta) ? zeta : 0.5, L / double(minima.size()), false, &m, curvature));
      out.back().dip = true;
    }
  } else if (!point) {  // each narrow minimum to the nearest element not yet taken
    std::vector<char> taken(placed.size(), 0);
    for (const Element& m : minima) {
      const double zeta = zetaOf(m);
      std::size_t k = placed.size();
      for (std::size_t c = 0; c < placed.size(); ++c)
        if (!taken[c] && (k == placed.size() || std::abs(placed[c].first - zeta) < std::abs(placed[k].first - zeta))) k = c;
      if (k == placed.size()) break;
      taken[k] = 1;
      out[k] = element(placed[k].first, placed[k].second, true, &m, curvature);
    }
  }
  return out;
}

}  // namespace fibra::reference
