// Small seeded fibre assemblies and helpers for the contact detection tests.
#pragma once

#include "store_bits.h"

#include "bench/contact_assemblies.h"
#include "components/contact.h"
#include "components/contact_cache.h"
#include "systems/contact_detection.h"
#include "engine/contact_setup.h"
#include "systems/contact_params.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

namespace fibra::fixtures {

using assemblies::add;
using assemblies::polylineFibre;

inline FibreDef helixFibre(double R, int elements, const Vec3& origin, const Vec3& axis,
                           double radius, double pitch, double turns, double phase) {
  FibreDef d;
  d.name = "h";
  d.radius = R;
  d.elements = elements;
  d.order = 2;
  d.geometry.kind = GeometryKind::Helix;
  d.geometry.origin = origin;
  d.geometry.axis = axis;
  d.geometry.helixRadius = radius;
  d.geometry.pitch = pitch;
  d.geometry.turns = turns;
  d.geometry.phase = phase;
  return d;
}

// Straight fibres at random places and directions in a small slab.
inline FibreStore straight(unsigned seed) { return assemblies::randomMat(14, 6, 1.0, 0.05, 0.15, seed); }

// Orders 2 and 1 alternating, kinked polylines.
inline FibreStore mixedOrders(unsigned seed) {
  return assemblies::randomMat(14, 5, 1.0, 0.05, 0.15, seed, 0.3, true);
}

// Helices about random axes through a common region, and kinked polylines.
inline FibreStore curved(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  FibreStore fs = assemblies::randomMat(6, 6, 1.0, 0.05, 0.08, seed + 1, 0.5);
  for (int k = 0; k < 6; ++k) {
    const Vec3 axis = Vec3(u(rng), u(rng), 0.3 * u(rng)).normalized();
    add(fs, helixFibre(0.05, 8, Vec3(0.6 + 0.3 * u(rng), 0.6 + 0.3 * u(rng), 0.15 * u(rng)), axis,
                       0.1 + 0.05 * u(rng), 0.6, 1.3, 3 * u(rng)));
  }
  return fs;
}

// Two layers of straight fibres, the second at random angles, their centrelines 1.8 R to 2.6 R
// apart: crossings at every angle.
inline FibreStore crossing(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double R = 0.05;
  FibreStore fs;
  for (int k = 0; k < 6; ++k) {
    const double y = 0.15 + 0.14 * k + 0.02 * u(rng);
    add(fs, polylineFibre("a", R, 6, 2, {Vec3(0, y, 0), Vec3(1, y + 0.1 * (u(rng) - 0.5), 0)}));
  }
  for (int k = 0; k < 6; ++k) {
    const double a = std::numbers::pi * (0.1 + 0.8 * u(rng)), z = R * (1.8 + 0.8 * u(rng));
    const Vec3 c(0.2 + 0.6 * u(rng), 0.3 + 0.5 * u(rng), z), d(std::cos(a), std::sin(a), 0);
    add(fs, polylineFibre("b", R, 5, 2, {c - 0.6 * d, c + 0.6 * d}));
  }
  return fs;
}

// A bundle of nearly parallel fibres (angles up to 4 deg) about 2.1 R apart.
inline FibreStore nearlyParallel(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double R = 0.05;
  FibreStore fs;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) {
      const Vec3 c(0.5, 2.1 * R * (i + 0.5 * (j % 2)), 1.85 * R * j);
      const Vec3 d = Vec3(1, 0.035 * u(rng), 0.035 * u(rng)).normalized();
      add(fs, polylineFibre("p", R, 6, 2, {c - 0.5 * d + 0.2 * R * Vec3(u(rng), u(rng), 0), c + 0.5 * d}));
    }
  return fs;
}

// Fibres along x and y with nodes at the same spacing, crossing exactly over nodes (and a pair
// touching end to end along x): closest points fall on element ends.
inline FibreStore elementEnds() {
  const double R = 0.05, h = 0.2;
  FibreStore fs;
  for (int k = 0; k < 3; ++k)
    add(fs, polylineFibre("x", R, 5, 2, {Vec3(0, k * h, 0), Vec3(5 * h, k * h, 0)}));
  for (int k = 0; k < 3; ++k)
    add(fs, polylineFibre("y", R, 5, 2, {Vec3(k * h + h, -h, 2.1 * R), Vec3(k * h + h, 4 * h, 2.1 * R)}));
  add(fs, polylineFibre("e", R, 5, 1, {Vec3(5 * h + 2.2 * R, 0, 0), Vec3(10 * h, 0, 0)}));
  return fs;
}

// A copy of the state with every node moved by up to `amplitude` (mm, uniform per component)
// and its directors deformed into an ellipse: g1 stretched by 1.3, g2 shrunk to 0.8 and sheared.
inline Eigen::VectorXd deformed(const FibreStore& fs, unsigned seed, double amplitude,
                                bool ellipticalSections = true) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd q = fs.q;
  for (Index n = 0; n < fs.nodes(); ++n) {
    x0Of(q, n) += amplitude * Vec3(u(rng), u(rng), u(rng));
    if (!ellipticalSections) continue;
    const Vec3 g1 = g1Of(q, n), g2 = g2Of(q, n);
    g1Of(q, n) = 1.3 * g1;
    g2Of(q, n) = 0.8 * g2 + 0.25 * g1;
  }
  return q;
}

using test::sameBits;

// The stores one detection call fills, and its report.
struct Detected {
  ContactCache cache;
  ZoneStore zones;
  ContactElementStore el;
  ContactDetectionReport report;
};

inline void detect(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                   Detected& d) {
  d.report = detectContacts(fs, q, p, d.cache, d.zones, d.el);
}

// A strand bent round a fibre (tests/test_contact_minima.cpp): I straight along x (R, elementsI
// quadratic elements, x in [-1, 1]); J of 3 quadratic elements (reference length lengthJ, mm: the
// element length that sets the zone's element spacing) in the plane x = y whose middle
// element has the nodes (-w, -w, z0 + k), (0, 0, z0), (w, w, z0 + k), with k^2 = 16 (z0^2 - rho^2)
// and w^2 = -k^2 / 2 - 2 k z0: its distance from I's axis has minima rho at xi = -+1/2 (s = 1.25 h
// and 1.75 h on J, h = J's element length) and the ridge z0 at xi = 0; its outer elements lead
// away along its end tangents; `tilt` (mm) adds tilt xi to z along the middle element (its end
// nodes -+tilt), which lowers one minimum and raises the other. The state q (the fibres'
// directors those of the straight start).
struct BentRound {
  FibreStore fs;
  Eigen::VectorXd q;
  double w;  // mm
};

inline BentRound bentRound(double R, int elementsI, double lengthJ, double rho, double z0,
                           double tilt = 0) {
  BentRound b;
  const double k = -4 * std::sqrt(z0 * z0 - rho * rho);
  b.w = std::sqrt(-0.5 * k * k - 2 * k * z0);
  add(b.fs, polylineFibre("i", R, elementsI, 2, {Vec3(-1, 0, 0), Vec3(1, 0, 0)}));
  add(b.fs, polylineFibre("j", R, 3, 2, {Vec3(0, -lengthJ / 2, 0), Vec3(0, lengthJ / 2, 0)}));
  b.q = b.fs.q;
  const double w = b.w;
  const Vec3 left(-w, -w, z0 + k - tilt), mid(0, 0, z0), right(w, w, z0 + k + tilt);
  const Vec3 tLeft = Vec3(w, w, -2 * k + tilt).normalized();
  const Vec3 tRight = Vec3(w, w, 2 * k + tilt).normalized();
  const Vec3 nodes[7] = {left - 0.6 * tLeft, left - 0.3 * tLeft, left, mid,
                         right, right + 0.3 * tRight, right + 0.6 * tRight};
  for (int n = 0; n < 7; ++n) b.q.segment<3>(kNodeDofs * (b.fs.firstNode[1] + n)) = nodes[n];
  return b;
}

// Detection parameters with every default derived from the fibres.
inline ContactParams defaults(const FibreStore& fs) {
  return resolveContactParams(fs, ContactDef{});
}

}  // namespace fibra::fixtures
