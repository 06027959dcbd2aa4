// The yarn generator: spec reading, hexagonal section, helical and perturbed centrelines, and
// the scene entries they expand into (the formulas are in yarn_generator.h).
#include "io/yarn_generator.h"

#include "io/generator_fields.h"
#include "io/generators.h"
#include "io/seeded_random.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace fibra {
namespace {

using namespace generator_fields;

// The seed: a whole number from 0 to 2^53 (a double holds every whole number up to there, so
// 5e6 and 5000000.0 read as 5000000 and nothing is rounded).
std::uint64_t readSeed(const Fields& f) {
  constexpr std::uint64_t kMax = std::uint64_t(1) << 53;
  const char* range = "a whole number from 0 to 9007199254740992 (2^53)";
  const Json& j = f.at("seed");
  if (!j.is_number()) bad(f, "seed", json_reader::typeMismatch(range, j));
  if (j.is_number_unsigned() && j.get<std::uint64_t>() <= kMax) return j.get<std::uint64_t>();
  const double v = j.get<double>();
  if (!j.is_number_unsigned() && v >= 0 && v <= double(kMax) && v == std::floor(v))
    return std::uint64_t(v);
  bad(f, "seed", std::string("must be ") + range + ", got " + json_reader::shown(j.dump()));
}

YarnPerturbation readPerturbation(const Json& j, const std::string& path, const YarnDef& y) {
  const Fields f(j, path, {"amplitude", "modes", "min_wavelength", "seed"});
  YarnPerturbation p;
  p.amplitude = f.number("amplitude");
  if (!(p.amplitude >= 0 && std::isfinite(p.amplitude)))
    bad(f, "amplitude", "must be >= 0, got " + num(p.amplitude));
  p.modes = integerIn(f, "modes", p.modes, 1, 100);
  const double element = y.length / y.elements;
  p.minWavelength = std::max(y.length / 2, 2 * element);
  if (f.has("min_wavelength")) p.minWavelength = positive(f, "min_wavelength");
  if (p.minWavelength > 2 * y.length)
    bad(f, "min_wavelength", "must be at most twice the length (" + num(2 * y.length) +
                                 " mm), got " + num(p.minWavelength));
  if (p.minWavelength < 2 * element)
    bad(f, "min_wavelength", "must be at least two element lengths (" + num(2 * element) +
                                 " mm: a shorter wave is not represented), got " +
                                 num(p.minWavelength));
  p.seed = readSeed(f);
  return p;
}

}  // namespace

YarnDef readYarn(const Json& spec, const std::string& path) {
  const Fields f(spec, path,
                 {"type", "name", "material", "fibres", "fibre_radius", "gap", "length",
                  "elements", "order", "origin", "axis", "twist", "perturbation"},
                 "a yarn generator");
  YarnDef y;
  y.name = f.string("name");
  checkName(f, y.name);
  y.material = f.string("material");
  y.fibres = integerIn(f, "fibres", 0, 1, 100000);
  y.fibreRadius = positive(f, "fibre_radius");
  y.gap = f.number("gap", y.gap);
  if (!(y.gap >= 0 && std::isfinite(y.gap))) bad(f, "gap", "must be >= 0, got " + num(y.gap));
  y.length = positive(f, "length");
  y.elements = integerIn(f, "elements", 0, 1, 100000);
  checkElementCount(f, y.fibres, y.elements);
  y.order = f.integer("order", y.order);
  if (y.order != 1 && y.order != 2)
    bad(f, "order", "must be 1 or 2, got " + std::to_string(y.order));
  y.origin = f.vec3("origin", y.origin);
  if (!y.origin.allFinite()) bad(f, "origin", "must be a finite vector");
  y.axis = f.vec3("axis", y.axis);
  if (!(y.axis.allFinite() && y.axis.norm() > 0)) bad(f, "axis", "must be a finite, non-zero vector");
  y.axis.normalize();
  y.twist = f.number("twist", y.twist);
  if (!std::isfinite(y.twist)) bad(f, "twist", "must be a finite number");
  if (f.has("perturbation"))
    y.perturbation = readPerturbation(f.at("perturbation"), f.path("perturbation"), y);
  return y;
}

std::vector<std::array<double, 2>> hexagonalLayout(int count, double spacing) {
  std::vector<std::array<double, 2>> sites{{0.0, 0.0}};
  for (int ring = 1; int(sites.size()) < count; ++ring) {
    std::vector<std::array<double, 2>> ringSites;  // 6 ring sites, counter-clockwise from +x
    for (int side = 0; side < 6; ++side) {
      const double a0 = side * std::numbers::pi / 3, a1 = (side + 1) * std::numbers::pi / 3;
      const double x0 = ring * spacing * std::cos(a0), y0 = ring * spacing * std::sin(a0);
      const double x1 = ring * spacing * std::cos(a1), y1 = ring * spacing * std::sin(a1);
      for (int j = 0; j < ring; ++j)
        ringSites.push_back({x0 + (x1 - x0) * j / ring, y0 + (y1 - y0) * j / ring});
    }
    const int wanted = std::min<int>(count - int(sites.size()), int(ringSites.size()));
    for (int j = 0; j < wanted; ++j)  // evenly spread when the ring is filled partially
      sites.push_back(ringSites[size_t(j) * ringSites.size() / wanted]);
  }
  sites.resize(count);
  return sites;
}

std::array<Vec3, 2> yarnSectionAxes(const Vec3& axis) {
  const Vec3 a = axis.normalized();
  int least = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(a(c)) < std::abs(a(least))) least = c;
  const Vec3 e1 = (Vec3::Unit(least) - a(least) * a).normalized();
  return {e1, a.cross(e1)};
}

namespace {

// One transverse offset u(s) = sum_m c_m sin(k_m pi s / L): wave numbers and coefficients.
struct SineModes {
  std::vector<int> k;
  std::vector<double> c;  // mm
  double at(double s, double length) const {
    double u = 0;
    for (size_t m = 0; m < k.size(); ++m) u += c[m] * std::sin(k[m] * std::numbers::pi * s / length);
    return u;
  }
};

SineModes drawModes(SeededRandom& random, const YarnDef& y) {
  const YarnPerturbation& p = y.perturbation;
  const int kMax = std::max(1, int(std::floor(2 * y.length / p.minWavelength)));
  SineModes modes;
  double sum = 0;
  for (int m = 0; m < p.modes; ++m) {
    modes.k.push_back(1 + random.below(kMax));
    modes.c.push_back(2 * random.uniform() - 1);
    sum += std::abs(modes.c.back());
  }
  for (double& c : modes.c) c = sum > 0 ? c * p.amplitude / sum : 0.0;
  return modes;
}

std::vector<Vec3> centreline(const YarnDef& y, const std::array<double, 2>& site,
                             const std::array<Vec3, 2>& e, const SineModes& u1,
                             const SineModes& u2) {
  const int segments = kYarnPointsPerElement * y.elements;
  std::vector<Vec3> points;
  for (int i = 0; i <= segments; ++i) {
    const double s = y.length * i / segments;
    const double phi = 2 * std::numbers::pi * y.twist * s / y.length;
    const double x = site[0] * std::cos(phi) - site[1] * std::sin(phi);
    const double z = site[0] * std::sin(phi) + site[1] * std::cos(phi);
    points.push_back(y.origin + s * y.axis + (x + u1.at(s, y.length)) * e[0] +
                     (z + u2.at(s, y.length)) * e[1]);
  }
  return points;
}

Json vec(const Vec3& v) { return Json::array({v(0), v(1), v(2)}); }

Json fibreJson(const YarnDef& y, int k, const std::vector<Vec3>& points, const Vec3& director) {
  Json pts = Json::array();
  for (const Vec3& p : points) pts.push_back(vec(p));
  return {{"name", y.name + ".f" + std::to_string(k)},
          {"material", y.material},
          {"radius", y.fibreRadius},
          {"elements", y.elements},
          {"order", y.order},
          {"geometry", {{"type", "polyline"}, {"points", pts}, {"director", vec(director)}}}};
}

Json unionJson(const YarnDef& y, const std::string& suffix) {
  Json members = Json::array();
  for (int k = 0; k < y.fibres; ++k) members.push_back(y.name + ".f" + std::to_string(k) + suffix);
  return {{"name", y.name + suffix}, {"union", members}};
}

}  // namespace

std::vector<std::vector<Vec3>> yarnCentrelines(const YarnDef& y) {
  const auto sites = hexagonalLayout(y.fibres, 2 * y.fibreRadius + y.gap);
  const auto e = yarnSectionAxes(y.axis);
  SeededRandom random(y.perturbation.seed);
  std::vector<std::vector<Vec3>> lines;
  for (const auto& site : sites) {
    SineModes u1, u2;
    if (y.perturbation.amplitude > 0) {
      u1 = drawModes(random, y);
      u2 = drawModes(random, y);
    }
    lines.push_back(centreline(y, site, e, u1, u2));
  }
  return lines;
}

void expandYarn(const Json& spec, const std::string& path, Json& scene) {
  const YarnDef y = readYarn(spec, path);
  const auto lines = yarnCentrelines(y);
  const Vec3 director = yarnSectionAxes(y.axis)[0];
  Json& fibres = sceneList(scene, "fibres");
  for (int k = 0; k < y.fibres; ++k) fibres.push_back(fibreJson(y, k, lines[k], director));
  Json& groups = sceneList(scene, "groups");
  for (const char* suffix : {".start", ".end", ".all"}) groups.push_back(unionJson(y, suffix));
}

}  // namespace fibra
