// Reference solution shared by the large-deflection test and the cantilever bench: the
// inextensible elastica of a cantilever under a dead tip load normal to it.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace fibra {

// lambda = P L^2 / EI, arc length u in [0, 1]: theta'' = lambda cos(theta), theta(0) = 0,
// theta'(1) = 0 (load along -y). Returns the tip (x, y) / L. RK4 on (theta, theta', x, y) with
// 4000 steps; bisection on theta'(0) in [-lambda, 0], where theta'(1) changes sign.
inline Eigen::Vector2d elasticaTip(double lambda) {
  auto integrate = [lambda](double k, Eigen::Vector2d& tip) {
    const int n = 4000;
    const double h = 1.0 / n;
    Eigen::Vector4d y(0, k, 0, 0);
    auto rhs = [lambda](const Eigen::Vector4d& s) {
      return Eigen::Vector4d(s(1), lambda * std::cos(s(0)), std::cos(s(0)), std::sin(s(0)));
    };
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector4d k1 = rhs(y), k2 = rhs(y + 0.5 * h * k1), k3 = rhs(y + 0.5 * h * k2),
                            k4 = rhs(y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    tip = y.tail<2>();
    return y(1);
  };
  double lo = -lambda, hi = 0;
  Eigen::Vector2d tip;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (integrate(mid, tip) > 0 ? hi : lo) = mid;
  }
  integrate(0.5 * (lo + hi), tip);
  return tip;
}

}  // namespace fibra
