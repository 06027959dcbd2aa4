// Independent geometric measures for tests: a fibre's centreline from its nodes and the closest
// approach of two centrelines by sampling (no use of the contact systems).
#pragma once

#include "components/fibres.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <utility>

namespace fibra::test {

// The nodal vector at `offset` in each node's DOFs (0: x0, 3: g1, 6: g2) of fibre f at s,
// quadratic Lagrange on each of its equal elements.
inline Vec3 interpolated(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s,
                         int offset) {
  const Index n = fs.elementCount[f];
  const double h = fs.length[f] / n;
  const Index e = std::clamp<Index>(Index(s / h), 0, n - 1);
  const double xi = 2 * (s - e * h) / h - 1;
  const Index a = fs.firstNode[f] + 2 * e;
  const double N[3] = {0.5 * xi * (xi - 1), 1 - xi * xi, 0.5 * xi * (xi + 1)};
  Vec3 v = Vec3::Zero();
  for (int k = 0; k < 3; ++k) v += N[k] * q.segment<3>(kNodeDofs * (a + k) + offset);
  return v;
}

// x0(s) of fibre f from its nodes, mm.
inline Vec3 centreline(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s) {
  return interpolated(fs, q, f, s, 0);
}

struct Closest {
  double distance;  // mm
  Vec3 fromJtoI;
  double sI = 0, sJ = 0;  // where, on I and J, mm
};

// The directors g1, g2 of fibre f at s from its nodes.
inline std::pair<Vec3, Vec3> directors(const FibreStore& fs, const Eigen::VectorXd& q, Index f,
                                       double s) {
  return {interpolated(fs, q, f, s, 3), interpolated(fs, q, f, s, 6)};
}

// Closest approach of the centrelines of I and J within `within` mm of sI0 on I and sJ0 on J
// (mm): sampled every 5 um, then every 0.05 um within 10 um of the best pair (in the windows).
inline Closest closestApproach(const FibreStore& fs, const Eigen::VectorXd& q, Index I, Index J,
                               double sI0, double sJ0, double within = 0.5) {
  const double loI = std::max(0.0, sI0 - within), hiI = std::min(fs.length[I], sI0 + within);
  const double loJ = std::max(0.0, sJ0 - within), hiJ = std::min(fs.length[J], sJ0 + within);
  double bestI = sI0, bestJ = sJ0, best = 1e300;
  for (double step : {5e-3, 5e-5}) {
    const double cI = bestI, cJ = bestJ, span = step == 5e-3 ? within : 1e-2;
    for (double a = std::max(loI, cI - span); a <= std::min(hiI, cI + span); a += step)
      for (double b = std::max(loJ, cJ - span); b <= std::min(hiJ, cJ + span); b += step) {
        const double d = (centreline(fs, q, I, a) - centreline(fs, q, J, b)).norm();
        if (d < best) best = d, bestI = a, bestJ = b;
      }
  }
  return {best, centreline(fs, q, I, bestI) - centreline(fs, q, J, bestJ), bestI, bestJ};
}

// The true overlap of I and J at their closest approach c: w_I + w_J - d, w = R |G^T n| each
// fibre's half-width along the line of centres n (G = [g1 g2] its deformed directors there: a
// flattened section is narrower), mm.
inline double overlapAt(const FibreStore& fs, const Eigen::VectorXd& q, Index I, Index J,
                        const Closest& c) {
  const Vec3 n = c.fromJtoI / c.distance;
  const auto width = [&](Index f, double s) {
    const auto [g1, g2] = directors(fs, q, f, s);
    return fs.radius[f] * std::hypot(g1.dot(n), g2.dot(n));
  };
  return width(I, c.sI) + width(J, c.sJ) - c.distance;
}

// Distance from p to fibre f's centreline within [sa, sb] (mm): sampled every 2 um, then a
// golden-section search around the best sample.
inline double distanceToCentreline(const FibreStore& fs, const Eigen::VectorXd& q, Index f,
                                   const Vec3& p, double sa, double sb) {
  const auto d = [&](double s) { return (centreline(fs, q, f, s) - p).norm(); };
  const int n = std::max(2, int(std::ceil((sb - sa) / 2e-3)));
  double best = sa;
  for (int i = 1; i <= n; ++i)
    if (const double s = sa + (sb - sa) * i / n; d(s) < d(best)) best = s;
  double lo = std::max(sa, best - (sb - sa) / n), hi = std::min(sb, best + (sb - sa) / n);
  const double r = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 80; ++k) {
    const double u = hi - r * (hi - lo), v = lo + r * (hi - lo);
    if (d(u) < d(v)) hi = v;
    else lo = u;
  }
  return std::min(d(best), d(0.5 * (lo + hi)));
}

// How deep the end disc of fibre f (its start when `start`, else its end) reaches into fibre o:
// the largest R_o - |x - x0_o| over the disc x = x0 + xi1 g1 + xi2 g2, |xi| <= R_f (directors
// from the nodes), on a polar grid of `rings` x `angles` points, the distance to o's centreline
// within [sa, sb] by distanceToCentreline (mm; negative: the disc clear of o by that much).
inline double endDiscDepth(const FibreStore& fs, const Eigen::VectorXd& q, Index f, bool start,
                           Index o, double sa, double sb, int rings = 20, int angles = 180) {
  const double s = start ? 0 : fs.length[f], R = fs.radius[f];
  const Vec3 x0 = centreline(fs, q, f, s);
  const auto [g1, g2] = directors(fs, q, f, s);
  double deepest = -1e300;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < (i == 0 ? 1 : angles); ++j) {
      const double r = R * i / rings, phi = 2 * 3.14159265358979323846 * j / angles;
      const Vec3 x = x0 + r * std::cos(phi) * g1 + r * std::sin(phi) * g2;
      deepest = std::max(deepest, fs.radius[o] - distanceToCentreline(fs, q, o, x, sa, sb));
    }
  return deepest;
}

}  // namespace fibra::test
