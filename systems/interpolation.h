// Interpolation along a fibre: Lagrange shape functions of the beam elements, Gauss-Legendre
// rules, and the section of a fibre at a reference arc length s.
//
// An element maps its parameter z in [-1, 1] to s = s_a + (z + 1) h / 2, h its reference length,
// and interpolates every nodal field u (x0, g1, g2) as u(z) = sum_a N_a(z) u_a, with nodes at
// z = -1, 1 (order 1) or z = -1, 0, 1 (order 2). Header-only: used by the beam element and by
// the contact systems alike.
#pragma once

#include "components/fibres.h"

#include <algorithm>
#include <cmath>

namespace fibra {

// N_a(z) and dN_a/dz for the order-1 or order-2 Lagrange element.
inline void lagrangeShape(int order, double z, double* N, double* dN) {
  if (order == 1) {
    N[0] = 0.5 * (1 - z);
    N[1] = 0.5 * (1 + z);
    dN[0] = -0.5;
    dN[1] = 0.5;
  } else {
    N[0] = 0.5 * z * (z - 1);
    N[1] = 1 - z * z;
    N[2] = 0.5 * z * (z + 1);
    dN[0] = z - 0.5;
    dN[1] = -2 * z;
    dN[2] = z + 0.5;
  }
}

// Gauss-Legendre points and weights on [-1, 1] for any n >= 1 (exact for degree 2n - 1), in
// increasing z: the roots of the Legendre polynomial P_n by Newton's method from
// cos(pi (k + 3/4) / (n + 1/2)), P_n and P_n' by the three-term recurrence, w = 2 / ((1 - z^2)
// P_n'(z)^2) (Abramowitz & Stegun 25.4.29). Used where n exceeds the tabulated rules below.
inline void gaussLegendreAny(int n, double* z, double* w) {
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < (n + 1) / 2; ++k) {
    double x = std::cos(pi * (k + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;  // P_0, P_1
      for (int j = 2; j <= n; ++j) {
        const double p2 = ((2 * j - 1) * x * p1 - (j - 1) * p0) / j;
        p0 = p1, p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);  // P_n' from P_n and P_{n-1}
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double weight = 2 / ((1 - x * x) * dp * dp);
    z[k] = -x, z[n - 1 - k] = x;
    w[k] = w[n - 1 - k] = weight;
  }
  if (n % 2 == 1) z[n / 2] = 0;  // the middle root, exactly
}

// Gauss-Legendre points and weights on [-1, 1] (exact for degree 2n - 1): n = 1..4 tabulated,
// larger n computed (gaussLegendreAny).
inline void gaussLegendre(int n, double* z, double* w) {
  switch (n) {
    case 1:
      z[0] = 0;
      w[0] = 2;
      return;
    case 2: {
      const double a = 1 / std::sqrt(3.0);
      z[0] = -a, z[1] = a;
      w[0] = w[1] = 1;
      return;
    }
    case 3: {
      const double a = std::sqrt(0.6);
      z[0] = -a, z[1] = 0, z[2] = a;
      w[0] = w[2] = 5.0 / 9, w[1] = 8.0 / 9;
      return;
    }
    case 4: {
      const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(1.2));
      const double b = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(1.2));
      const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
      z[0] = -b, z[1] = -a, z[2] = a, z[3] = b;
      w[0] = w[3] = wb, w[1] = w[2] = wa;
      return;
    }
    default:
      gaussLegendreAny(n, z, w);
  }
}

// A point on a fibre: its element and the element parameter z in [-1, 1].
struct FibrePoint {
  Index element = -1;
  double z = 0;
};

// Element length h = L / n of fibre f, mm.
inline double elementLength(const FibreStore& fs, Index f) {
  return fs.length[f] / fs.elementCount[f];
}

// The element and parameter of reference arc length s (clamped to [0, L]) on fibre f.
inline FibrePoint locate(const FibreStore& fs, Index f, double s) {
  const double h = elementLength(fs, f);
  const Index n = fs.elementCount[f];
  const double t = std::clamp(s, 0.0, fs.length[f]) / h;
  const Index i = std::min<Index>(Index(t), n - 1);
  return {fs.firstElement[f] + i, 2 * (t - i) - 1};
}

// Reference arc length of parameter z on element e, mm.
inline double arcLength(const FibreStore& fs, Index e, double z) {
  const Index f = fs.elementFibre[e];
  const double h = elementLength(fs, f);
  return (e - fs.firstElement[f] + 0.5 * (z + 1)) * h;
}

// The section at a fibre point, interpolated from a [x0 g1 g2] state vector q:
// centroid x0 (mm), derivative dx0/ds along the reference arc length (-), directors g1, g2.
struct Section {
  Vec3 x0, dx0ds, g1, g2;
};

inline Section sectionAt(const FibreStore& fs, const Eigen::VectorXd& q, FibrePoint p) {
  const Index f = fs.elementFibre[p.element];
  const int order = fs.order[f];
  double N[3], dN[3];
  lagrangeShape(order, p.z, N, dN);
  const double dzds = 2 / elementLength(fs, f);
  Section sec{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (int a = 0; a <= order; ++a) {
    const Index n = fs.elementFirstNode[p.element] + a;
    sec.x0 += N[a] * x0Of(q, n);
    sec.dx0ds += dN[a] * dzds * x0Of(q, n);
    sec.g1 += N[a] * g1Of(q, n);
    sec.g2 += N[a] * g2Of(q, n);
  }
  return sec;
}

}  // namespace fibra
