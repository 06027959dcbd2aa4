#include "systems/contact_intermediate.h"

namespace fibra {

double intermediateLength(const Intermediate& g) {
  if (g.dI == 0 && g.dJ == 0) return 0;
  Breakpoints bI(g.sI1, g.dI, elementLength(g.fs, g.I)), bJ(g.sJ1, g.dJ, elementLength(g.fs, g.J));
  const double r = 0.5 / std::sqrt(3.0);
  double a = 0, total = 0;
  while (a < 1) {
    const double zI = bI.peek(), zJ = bJ.peek(), b = std::min(zI, zJ);
    if (b > a) {
      const double mid = 0.5 * (a + b), w = b - a;
      total += 0.5 * w * (g.tangent(mid - r * w).norm() + g.tangent(mid + r * w).norm());
    }
    if (zI == b && zI < 1) bI.advance();
    if (zJ == b && zJ < 1) bJ.advance();
    a = b;
  }
  return total;
}

double sectionAbscissa(const Intermediate& g, Index f, double s, double guess, double window) {
  const Vec3 x = centrelineAt(g.fs, g.cl, f, s).x;
  const bool onI = f == g.I;
  const Vec3 tHat = 0.5 * (centrelineTangent(g.fs, g.cl, f, s) * (onI ? g.dI : g.dJ) +
                           (onI ? centrelineTangent(g.fs, g.cl, g.J, g.sJ(guess)) * g.dJ
                                : centrelineTangent(g.fs, g.cl, g.I, g.sI(guess)) * g.dI));
  auto F = [&](double z) { return (g.position(z) - x).dot(tHat); };
  const double lo = std::max(0.0, guess - window), hi = std::min(1.0, guess + window);
  double a = 0, b = 0, fa = 0, fb = 0, nearest = 2;
  double z0 = lo, f0 = F(lo);
  for (int k = 1; k <= 8; ++k) {
    const double z1 = lo + (hi - lo) * k / 8, f1 = F(z1);
    const double distance = std::abs(0.5 * (z0 + z1) - guess);
    if ((f0 > 0) != (f1 > 0) && distance < nearest) a = z0, b = z1, fa = f0, fb = f1, nearest = distance;
    z0 = z1, f0 = f1;
  }
  if (nearest > 1) return guess;
  int side = 0;
  for (int it = 0; it < 60 && b - a > 1e-15; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa), fc = F(c);
    if ((fc > 0) == (fb > 0)) {
      b = c, fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c, fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
    if (fc == 0) return c;
  }
  return 0.5 * (a + b);
}

int simpsonParts(const Intermediate& g, double a, double b, double sag) {
  const double hI = elementLength(g.fs, g.I), hJ = elementLength(g.fs, g.J);
  const FibrePoint pI = locate(g.fs, g.I, g.sI(0.5 * (a + b)));
  const FibrePoint pJ = locate(g.fs, g.J, g.sJ(0.5 * (a + b)));
  const CentrelinePolynomial &PI = g.cl.poly[pI.element], &PJ = g.cl.poly[pJ.element];
  const double zI = 2 * g.dI / hI, zJ = 2 * g.dJ / hJ;  // dz/dzeta on I and J
  double K = (2 * PI.c * zI * zI - 2 * PJ.c * zJ * zJ).norm();
  const double floor = 0.5 * (g.fs.radius[g.I] + g.fs.radius[g.J]);
  double drift = 0;
  for (const double zeta : {a, b}) {
    const double z1 = std::clamp(pI.z + (zeta - 0.5 * (a + b)) * zI, -1.0, 1.0);
    const double z2 = std::clamp(pJ.z + (zeta - 0.5 * (a + b)) * zJ, -1.0, 1.0);
    const Vec3 D = PI.a + z1 * PI.b + z1 * z1 * PI.c - (PJ.a + z2 * PJ.b + z2 * z2 * PJ.c);
    const Vec3 dD = (PI.b + 2 * z1 * PI.c) * zI - (PJ.b + 2 * z2 * PJ.c) * zJ;
    const double d = D.norm();
    const double along = d > 0 ? dD.dot(D) / d : 0;
    drift = std::max(drift, (dD.squaredNorm() - along * along) / std::max(d, floor));
  }
  K += drift;
  if (!(sag > 0) || !(K > 0)) return 1;
  const double m = std::ceil(0.5 * (b - a) * std::sqrt(K / (8 * sag)) * (1 - 1e-12));
  return int(std::clamp(m, 1.0, double(kMaxSimpsonParts)));
}

}  // namespace fibra
