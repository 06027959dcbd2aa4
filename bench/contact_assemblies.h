// Fibre assemblies for the contact detection tests and benches: seeded random mats, the
// paper's plain-weave fabric (section 5.2) and twisted yarn (section 5.3). Header-only; every
// fibre is built by engine/fibre_builder.h (material index 0: detection needs no material).
// Names are built with append, not "m" + std::to_string(...): GCC 12 warns falsely
// (-Wrestrict) on the latter once inlined.
#pragma once

#include "engine/fibre_builder.h"

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace fibra::assemblies {

inline FibreDef polylineFibre(const std::string& name, double radius, int elements, int order,
                              std::vector<Vec3> points) {
  FibreDef d;
  d.name = name;
  d.radius = radius;
  d.elements = elements;
  d.order = order;
  d.geometry.kind = GeometryKind::Polyline;
  d.geometry.points = std::move(points);
  return d;
}

inline void add(FibreStore& fs, const FibreDef& d) {
  addFibre(fs, d, 0, "fibres[" + std::to_string(fs.fibres()) + "]");
}

// Random mat: `fibres` fibres of `elements` elements and length `length` (mm), radius R, in a
// slab W x W x W/4 sized for a fibre volume fraction `fraction`; directions mostly in-plane
// (|z| <= 0.3 before normalising). `bend` > 0 makes each fibre a 4-vertex polyline with random
// kinks of that relative size. Orders alternate 2, 1 when `mixedOrders`.
inline FibreStore randomMat(int fibres, int elements, double length, double R, double fraction,
                            unsigned seed, double bend = 0, bool mixedOrders = false) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double volume = fibres * std::numbers::pi * R * R * length / fraction;
  const double W = std::cbrt(4 * volume);
  FibreStore fs;
  for (int f = 0; f < fibres; ++f) {
    const Vec3 c(W * u(rng), W * u(rng), W / 4 * u(rng));
    Vec3 d(2 * u(rng) - 1, 2 * u(rng) - 1, 0.6 * u(rng) - 0.3);
    d.normalize();
    std::vector<Vec3> pts;
    const int segments = bend > 0 ? 3 : 1;
    Vec3 p = c - 0.5 * length * d;
    pts.push_back(p);
    for (int k = 0; k < segments; ++k) {
      Vec3 dk = d;
      if (bend > 0) dk = (d + bend * Vec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1)).normalized();
      p += length / segments * dk;
      pts.push_back(p);
    }
    add(fs, polylineFibre(std::string("m").append(std::to_string(f)), R, elements,
                          mixedOrders && f % 2 ? 1 : 2, pts));
  }
  return fs;
}

struct WovenDef {
  int warp = 5, weft = 5;        // yarns along x and along y
  int rows = 3, columns = 16;    // fibres of a yarn: rows (z) x columns (lateral), hex packed
  int elements = 40;             // per fibre (quadratic)
  double radius = 0.026;         // fibre radius, mm (paper: diameter 0.052 mm)
  double pitch = 1.0;            // yarn spacing, mm
  double clearance = 1.05;       // neighbour distance / 2R inside a yarn
  int samples = 320;             // polyline vertices per fibre
};

// Plain weave (paper section 5.2): warp yarn j at y = (j + 1/2) p undulates as
// z = A (-1)^j cos(pi (x / p - 1/2)), weft yarn i at x = (i + 1/2) p as the opposite, so that
// at every crossing one yarn lies on the other; A = half the yarn thickness. Each fibre is its
// yarn's centreline translated by its (lateral, vertical) place in the hex-packed section.
inline std::vector<FibreDef> wovenFibres(const WovenDef& w = {}) {
  std::vector<FibreDef> out;
  const double R = w.radius, dl = 2 * R * w.clearance, dv = std::sqrt(3.0) * R * w.clearance;
  const double A = 0.5 * ((w.rows - 1) * dv + 2 * R);
  const double span = w.pitch * std::max(w.warp, w.weft);
  auto yarn = [&](bool alongX, int index) {
    const double sign = index % 2 ? -1 : 1, c = (index + 0.5) * w.pitch;
    for (int r = 0; r < w.rows; ++r)
      for (int k = 0; k < w.columns; ++k) {
        const double lat = (k - 0.5 * (w.columns - 1) + (r % 2 ? 0.25 : -0.25)) * dl;
        const double v = (r - 0.5 * (w.rows - 1)) * dv;
        std::vector<Vec3> pts;
        for (int i = 0; i < w.samples; ++i) {
          const double t = span * i / (w.samples - 1);
          const double z = (alongX ? 1 : -1) * sign * A * std::cos(std::numbers::pi * (t / w.pitch - 0.5)) + v;
          pts.push_back(alongX ? Vec3(t, c + lat, z) : Vec3(c + lat, t, z));
        }
        out.push_back(polylineFibre((alongX ? "warp" : "weft") + std::to_string(index), R,
                                    w.elements, 2, pts));
      }
  };
  for (int j = 0; j < w.warp; ++j) yarn(true, j);
  for (int i = 0; i < w.weft; ++i) yarn(false, i);
  return out;
}

inline FibreStore wovenFabric(const WovenDef& w = {}) {
  FibreStore fs;
  for (const FibreDef& d : wovenFibres(w)) add(fs, d);
  return fs;
}

struct YarnDef {
  int fibres = 250;
  int elements = 15;
  double radius = 0.01;     // mm (paper: diameter 0.02 mm)
  double length = 1.5;      // axial length, mm
  double pitch = 3.0;       // twist pitch, mm per turn
  double clearance = 1.02;  // ring spacing and in-ring spacing / 2R
};

// Twisted yarn (paper section 5.3): fibres on concentric rings (radius k 2R c, as many as fit
// at spacing 2R c), each a helix about the yarn axis z with the common pitch: a compact
// parallel packing, twisted.
inline std::vector<FibreDef> yarnFibres(const YarnDef& y = {}) {
  std::vector<FibreDef> out;
  const double d = 2 * y.radius * y.clearance;
  int made = 0;
  for (int ring = 0; made < y.fibres; ++ring) {
    const double r = ring * d;
    const int n = ring == 0 ? 1 : int(std::floor(2 * std::numbers::pi * r / d));
    for (int k = 0; k < n && made < y.fibres; ++k, ++made) {
      FibreDef f;
      f.name = std::string("y").append(std::to_string(made));
      f.radius = y.radius;
      f.elements = y.elements;
      f.order = 2;
      f.geometry.kind = GeometryKind::Helix;
      f.geometry.helixRadius = r;
      f.geometry.pitch = y.pitch;
      f.geometry.turns = y.length / y.pitch;
      f.geometry.phase = 2 * std::numbers::pi * k / n + 0.37 * ring;
      out.push_back(f);
    }
  }
  return out;
}

inline FibreStore twistedYarn(const YarnDef& y = {}) {
  FibreStore fs;
  for (const FibreDef& d : yarnFibres(y)) add(fs, d);
  return fs;
}

}  // namespace fibra::assemblies
