#include "systems/contact_geometry.h"

#include <Eigen/Eigenvalues>

#include <limits>
#include <tuple>

namespace fibra {
namespace {

// g(z) = (x(z) - p).x'(z) = g0 + g1 z + g2 z^2 + g3 z^3 and D(z) = |x(z) - p|^2.
struct Quartic {
  double d0, g0, g1, g2, g3, cc;
  double D(double z) const { return d0 + z * (2 * g0 + z * (g1 + z * (2 * g2 / 3 + z * cc))); }
  double g(double z) const { return g0 + z * (g1 + z * (g2 + z * g3)); }
  double dg(double z) const { return g1 + z * (2 * g2 + z * 3 * g3); }
};

// The root of g in [u, v] where g(u) < 0 < g(v) and g rises: Newton, bisection when a step
// leaves the bracket.
double risingRoot(const Quartic& Q, double u, double v, double gu, double gv) {
  double z = u - gu * (v - u) / (gv - gu);
  for (int it = 0; it < 100; ++it) {
    const double gz = Q.g(z);
    if (gz == 0) return z;
    (gz < 0 ? u : v) = z;
    const double newton = z - gz / Q.dg(z);
    if (newton > u && newton < v) {
      // quadratic convergence: after a step of 1e-9 the error is of order 1e-18
      if (std::abs(newton - z) <= 1e-9) return newton;
      z = newton;
    } else {
      z = 0.5 * (u + v);
      if (v - u <= 1e-15) return z;
    }
  }
  return z;
}

}  // namespace

ClosestPoint closestOnPolynomial(const CentrelinePolynomial& P, const Vec3& p, double z0,
                                 double z1) {
  const Vec3 d = P.a - p;
  const double db = d.dot(P.b), dc = d.dot(P.c), bb = P.b.dot(P.b), bc = P.b.dot(P.c);
  const double cc = P.c.dot(P.c);
  const Quartic Q{d.dot(d), db, bb + 2 * dc, 3 * bc, 2 * cc, cc};
  if (cc == 0) {  // straight element: g is linear
    const double z = bb > 0 ? std::clamp(-db / bb, z0, z1) : z0;
    return {z, Q.D(z)};
  }
  // g'(z) = A z^2 + B z + C, A > 0; no real root: g rises everywhere, one minimum.
  const double A = 3 * Q.g3, B = 2 * Q.g2, C = Q.g1, disc = B * B - 4 * A * C;
  if (disc <= 0) {
    const double g0 = Q.g(z0);
    if (g0 >= 0) return {z0, Q.D(z0)};
    const double g1 = Q.g(z1);
    if (g1 <= 0) return {z1, Q.D(z1)};
    const double z = risingRoot(Q, z0, z1, g0, g1);
    return {z, Q.D(z)};
  }
  // Split points: the roots of g' inside (z0, z1); candidates: the ends and every piece where
  // g rises through 0.
  ClosestPoint best{z0, Q.D(z0)};
  auto consider = [&](double z) {
    const double D = Q.D(z);
    if (D < best.dist2 || (D == best.dist2 && z < best.z)) best = {z, D};
  };
  consider(z1);
  double cut[4] = {z0, 0, 0, 0};
  int n = 1;
  const double r = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  double r1 = r / A, r2 = r != 0 ? C / r : r1;
  if (r1 > r2) std::swap(r1, r2);
  if (r1 > z0 && r1 < z1) cut[n++] = r1;
  if (r2 > z0 && r2 < z1) cut[n++] = r2;
  cut[n++] = z1;
  double gu = Q.g(cut[0]);
  for (int i = 0; i + 1 < n; ++i) {
    const double gv = Q.g(cut[i + 1]);
    if (gu < 0 && gv > 0) consider(risingRoot(Q, cut[i], cut[i + 1], gu, gv));
    gu = gv;
  }
  return best;
}

ClosestOnFibre closestOnFibre(const FibreStore& fs, const CentrelineStore& cl, Index f,
                              const Vec3& p, double sa, double sb) {
  const double h = elementLength(fs, f);
  const FibrePoint a = locate(fs, f, sa), b = locate(fs, f, sb);
  const Index first = fs.firstElement[f];
  ClosestOnFibre best{sa, std::numeric_limits<double>::infinity()};
  for (Index e = a.element; e <= b.element; ++e) {
    const double z0 = e == a.element ? a.z : -1, z1 = e == b.element ? b.z : 1;
    const ClosestPoint c = closestOnPolynomial(cl.poly[e], p, z0, z1);
    const double s = (e - first + 0.5 * (c.z + 1)) * h;
    if (c.dist2 < best.dist2 || (c.dist2 == best.dist2 && s < best.s)) best = {s, c.dist2};
  }
  return best;
}

bool planeCut(const FibreStore& fs, const CentrelineStore& cl, Index f, const Vec3& xInt,
              const Vec3& t, double s0, const CentrelinePoint& c0, double sa, double sb,
              double& s) {
  auto F = [&](double u) {
    const CentrelinePoint c = centrelineAt(fs, cl, f, u);
    return std::pair{(c.x - xInt).dot(t), c.dxds.dot(t)};
  };
  const double h = elementLength(fs, f);
  double v = (c0.x - xInt).dot(t), dv = c0.dxds.dot(t);
  if (std::abs(dv) < kPlaneCutMinCosine * c0.dxds.norm()) return false;
  // Newton from s0 while it stays in the interval; a step below 1e-7 h leaves an error of
  // order (1e-7 h)^2 / h after it (quadratic convergence).
  double u = s0;
  for (int it = 0; it < 12 && dv != 0; ++it) {
    const double next = u - v / dv;
    if (!(next >= sa && next <= sb)) break;
    if (std::abs(next - u) <= 1e-7 * h) {
      s = next;
      return true;
    }
    u = next;
    std::tie(v, dv) = F(u);
  }
  // The sign changes of f at samples every h / 2 across [sa, sb]: bisect the one nearest s0.
  const int n = std::max(1, int(std::ceil((sb - sa) / (0.5 * h))));
  double lo = 0, hi = 0, nearest = std::numeric_limits<double>::infinity();
  double u0 = sa, f0 = F(sa).first;
  for (int i = 1; i <= n; ++i) {
    const double u1 = i == n ? sb : sa + (sb - sa) * i / n, f1 = F(u1).first;
    const bool root = f0 == 0 || (f1 != 0 && (f0 < 0) != (f1 < 0));
    const double dist = s0 < u0 ? u0 - s0 : (s0 > u1 ? s0 - u1 : 0);
    if (root && dist < nearest) lo = u0, hi = f0 == 0 ? u0 : u1, nearest = dist;
    u0 = u1, f0 = f1;
  }
  if (f0 == 0 && std::abs(sb - s0) < nearest) lo = hi = sb, nearest = 0;
  if (!(nearest < std::numeric_limits<double>::infinity())) return false;
  const double tol = 1e-13 * h;
  const bool loNegative = F(lo).first < 0;
  u = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && hi - lo > tol; ++it) {
    std::tie(v, dv) = F(u);
    if (v == 0) break;
    ((v < 0) == loNegative ? lo : hi) = u;
    double next = dv != 0 ? u - v / dv : u;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    u = next;
  }
  s = lo == hi ? lo : u;
  return true;
}

bool outlinePoint(const Vec3& g1, const Vec3& g2, double R, const Vec3& dir, double xi[2]) {
  const double m11 = g1.dot(g1), m12 = g1.dot(g2), m22 = g2.dot(g2);
  const double det = m11 * m22 - m12 * m12;
  if (!(det > 1e-12 * m11 * m22)) return false;
  const double r1 = g1.dot(dir), r2 = g2.dot(dir);
  const double a = (m22 * r1 - m12 * r2) / det, b = (m11 * r2 - m12 * r1) / det;
  if (!((a * g1 + b * g2).norm() > 1e-9 * dir.norm())) return false;
  const double n = std::sqrt(a * a + b * b);
  xi[0] = R * a / n;
  xi[1] = R * b / n;
  return true;
}

namespace {

// The point of S's disc nearest p: the projection G m of p - x0 onto the section plane,
// m = (G^T G)^-1 G^T (p - x0), kept within the rim (|m| <= R).
Eigen::Vector2d discProjection(const Section& S, double R, const Vec3& p) {
  Eigen::Matrix2d M;
  M << S.g1.dot(S.g1), S.g1.dot(S.g2), S.g1.dot(S.g2), S.g2.dot(S.g2);
  const Vec3 d = p - S.x0;
  Eigen::Vector2d m = M.inverse() * Eigen::Vector2d(S.g1.dot(d), S.g2.dot(d));
  if (m.norm() > R) m *= R / m.norm();
  return m;
}

}  // namespace

bool endFaceParticle(const FibreStore& fs, Index f, double s, const Section& S, const Vec3& c,
                     double R, double xi[2]) {
  const double L = fs.length[f], tol = 1e-9 * L;
  const double outward = s <= tol ? -1 : s >= L - tol ? 1 : 0;
  if (outward == 0 || (c - S.x0).dot(outward * S.dx0ds.normalized()) <= 1e-9 * R) return false;
  const Eigen::Vector2d m = discProjection(S, R, c);
  xi[0] = m(0), xi[1] = m(1);
  return true;
}

Eigen::Vector2d discPointNearestLine(const Section& S, double R, const Vec3& c, const Vec3& t,
                                     const Eigen::Vector2d& m) {
  Eigen::Matrix<double, 3, 2> G;
  G << S.g1, S.g2;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - t * t.transpose();
  const Eigen::Matrix2d A = G.transpose() * P * G;
  const Eigen::Vector2d b = -G.transpose() * (P * (S.x0 - c));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(A);
  const double l1 = eig.eigenvalues()(1), l2 = eig.eigenvalues()(0);  // l1 >= l2 >= 0
  const Eigen::Vector2d v1 = eig.eigenvectors().col(1), v2 = eig.eigenvectors().col(0);
  if (!(l1 > 0)) return m;
  if (l2 <= kFlatDisc * l1) {
    // Q depends on v1 . xi alone: its value c1, then the point of that chord nearest m.
    const double c1 = v1.dot(b) / l1;
    if (std::abs(c1) >= R) return (c1 > 0 ? R : -R) * v1;
    const double half = std::sqrt(R * R - c1 * c1), c2 = std::clamp(v2.dot(m), -half, half);
    return c1 * v1 + c2 * v2;
  }
  const auto at = [&](double mu) {
    return Eigen::Vector2d(v1 * (v1.dot(b) / (l1 + mu)) + v2 * (v2.dot(b) / (l2 + mu)));
  };
  if (at(0).norm() <= R) return at(0);
  double lo = 0, hi = b.norm() / R;  // |xi(hi)| <= |b| / hi = R
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mu = 0.5 * (lo + hi);
    (at(mu).norm() > R ? lo : hi) = mu;
  }
  const Eigen::Vector2d xi = at(hi);
  return xi * (R / xi.norm());
}

bool endFaceContact(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                    Index f, double s, const Section& S, Index o, double sep, double clearance,
                    double& so, Section& O, double xi[2]) {
  const double R = fs.radius[f];
  if (!endFaceParticle(fs, f, s, S, O.x0, R, xi)) return false;
  const double reach = elementLength(fs, o) + 2 * R;
  double sa = std::max(0.0, so - reach), sb = std::min(fs.length[o], so + reach);
  if (f == o) {  // self-contact: o's part stays sep from the end
    if (so < s) sb = std::min(sb, s - sep);
    else sa = std::max(sa, s + sep);
  }
  if (!(sa < sb)) return true;
  const auto point = [&](const Eigen::Vector2d& m) {
    return Vec3(S.x0 + m(0) * S.g1 + m(1) * S.g2);
  };
  Eigen::Vector2d m(xi[0], xi[1]);
  ClosestOnFibre at = closestOnFibre(fs, cl, o, point(m), sa, sb);
  for (int k = 0; k < 100; ++k) {
    const CentrelinePoint c = centrelineAt(fs, cl, o, at.s);
    // the disc point nearest the tangent line, and nearest the point itself (t = 0: P = I)
    const Eigen::Vector2d cand[2] = {discPointNearestLine(S, R, c.x, c.dxds.normalized(), m),
                                     discPointNearestLine(S, R, c.x, Vec3::Zero(), m)};
    const ClosestOnFibre a = closestOnFibre(fs, cl, o, point(cand[0]), sa, sb);
    const ClosestOnFibre b = closestOnFibre(fs, cl, o, point(cand[1]), sa, sb);
    const bool first = a.dist2 <= b.dist2;
    const ClosestOnFibre& best = first ? a : b;
    if (!(best.dist2 < at.dist2 - 1e-15 * R * R)) break;
    m = cand[first ? 0 : 1];
    at = best;
  }
  if (!(at.dist2 >= clearance * clearance)) return true;  // o's axis reached: the projection
  xi[0] = m(0), xi[1] = m(1);
  so = at.s;
  O = contactSection(fs, q, o, so);
  return true;
}

}  // namespace fibra
