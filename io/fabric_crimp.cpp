// The woven fabric's crimped start: yarn sections, the crimp height, the yarn axes' plateau and
// cosine-ramp profiles, the fibres as normal offsets of them, their level tables and the checks
// of the spacings (the formulas are in fabric_generator.h).
#include "io/fabric_generator.h"

#include "io/generator_fields.h"
#include "io/yarn_generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fibra {
namespace {

using generator_fields::num;
constexpr double kPi = std::numbers::pi;

// l_j of yarn `yarn` of the warp (warp = true) or weft at its crossing j: +1 where it goes over.
int crossingLevel(const FabricDef& f, bool warp, int yarn, int j) {
  const int warpUp = warp ? warpOver(f, j, yarn) : warpOver(f, yarn, j);
  return (warpUp == 1) == warp ? 1 : -1;
}

// Whether a yarn of the direction changes level between two consecutive crossings (the pattern
// repeats: one period of yarns and of crossings decides).
bool hasRamp(const FabricDef& f, bool warp) {
  const WeaveDirection &d = warp ? f.warp : f.weft, &across = warp ? f.weft : f.warp;
  const int yarnPeriod = int(warp ? f.pattern[0].size() : f.pattern.size());
  const int crossingPeriod = int(warp ? f.pattern.size() : f.pattern[0].size());
  for (int c = 0; c < std::min(d.yarns, yarnPeriod); ++c)
    for (int j = 0; j + 1 < std::min(across.yarns, crossingPeriod + 1); ++j)
      if (crossingLevel(f, warp, c, j) != crossingLevel(f, warp, c, j + 1)) return true;
  return false;
}

// Arc length of the polyline `points` from its start to where its coordinate `axis` reaches
// `to` (the coordinate increases along it), mm.
double arcLengthTo(const std::vector<Vec3>& points, int axis, double to) {
  double s = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double a = points[i](axis), b = points[i + 1](axis);
    const double l = (points[i + 1] - points[i]).norm();
    if (b >= to) return s + std::clamp((to - a) / (b - a), 0.0, 1.0) * l;
    s += l;
  }
  return s;
}

}  // namespace

YarnSection yarnSection(const WeaveDirection& d) {
  const auto sites = hexagonalLayout(d.fibresPerYarn, 2 * d.fibreRadius + d.gap);
  std::array<double, 2> lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const auto& site : sites)
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], site[i]), hi[i] = std::max(hi[i], site[i]);
  const auto exact = [&](double v) { return std::abs(v) < 1e-12 * d.fibreRadius ? 0.0 : v; };
  YarnSection s;
  for (const auto& site : sites)
    s.offsets.push_back(
        {exact(site[0] - (lo[0] + hi[0]) / 2), exact(site[1] - (lo[1] + hi[1]) / 2)});
  s.width = hi[0] - lo[0] + 2 * d.fibreRadius;
  s.thickness = hi[1] - lo[1] + 2 * d.fibreRadius;
  s.vMax = exact((hi[1] - lo[1]) / 2);
  return s;
}

double crimpHeight(const FabricDef& f) {
  return (yarnSection(f.warp).thickness + yarnSection(f.weft).thickness + f.warp.gap + f.weft.gap) /
         4;
}

std::array<double, 2> CrimpProfile::at(double x) const {
  const int n = int(level.size());
  const int j = int(std::clamp(std::floor((x - first) / spacing), 0.0, double(n - 1)));
  const double H = level[size_t(j)] * height;  // l_j H
  if (j == n - 1) return {H, 0};
  const double g = spacing - 2 * halfWidth, tau = (x - first - j * spacing - halfWidth) / g;
  if (tau <= 0 || level[size_t(j) + 1] == level[size_t(j)]) return {H, 0};
  if (tau >= 1) return {-H, 0};
  return {H * std::cos(kPi * tau), -H * kPi / g * std::sin(kPi * tau)};  // z, dz/dx
}

CrimpProfile crimpProfile(const FabricDef& f, bool warp, int c) {
  const WeaveDirection& across = warp ? f.weft : f.warp;
  CrimpProfile p;
  for (int j = 0; j < across.yarns; ++j) p.level.push_back(crossingLevel(f, warp, c, j));
  p.first = yarnAxisPosition(across, 0);
  p.spacing = across.spacing;
  p.halfWidth = yarnSection(across).width / 2;
  p.height = crimpHeight(f);
  return p;
}

std::vector<Vec3> crimpedCentreline(const FabricDef& f, bool warp, int c, int k) {
  const WeaveDirection& d = warp ? f.warp : f.weft;
  const auto [u, v] = yarnSection(d).offsets[size_t(k)];
  const CrimpProfile profile = crimpProfile(f, warp, c);
  const double across = yarnAxisPosition(d, c) + u, half = d.length / 2;
  const int segments = kCrimpPointsPerElement * d.elements;
  std::vector<Vec3> points;
  for (int i = 0; i <= segments; ++i) {
    const double x = -half + d.length * i / segments;
    const auto [z, slope] = profile.at(x);
    const double norm = std::hypot(1.0, slope);  // P = (x, z) + v (-z', 1)/sqrt(1 + z'^2)
    const double along = x - v * slope / norm, height = z + v / norm;
    points.push_back(warp ? Vec3(along, across, height) : Vec3(across, along, height));
  }
  return points;
}

std::vector<std::array<double, 2>> crimpedWarpLevels(const FabricDef& f, int c,
                                                      const std::vector<Vec3>& points) {
  std::vector<std::array<double, 2>> pieces;
  for (int r = 0; r < f.weft.yarns; ++r) {
    const double level = crossingLevel(f, true, c, r);
    const double mid = 0.5 * (yarnAxisPosition(f.weft, r - 1) + yarnAxisPosition(f.weft, r));
    const double from = r == 0 ? 0 : arcLengthTo(points, 0, mid);  // x halfway, on the fibre
    if (pieces.empty() || pieces.back()[1] != level) pieces.push_back({from, level});
  }
  return pieces;
}

void checkCrimp(const FabricDef& f, const std::string& path) {
  const double H = crimpHeight(f);
  for (bool warp : {true, false}) {  // the yarns of one direction ramp between the others
    const WeaveDirection& across = warp ? f.weft : f.warp;
    const std::string at = path + (warp ? ".weft" : ".warp") + ".spacing";
    const std::string acrossName = warp ? "weft" : "warp", name = warp ? "warp" : "weft";
    const WeaveDirection& own = warp ? f.warp : f.weft;
    const double w = yarnSection(across).width, vMax = yarnSection(own).vMax;
    const double bend = kCrimpBendRadii * own.fibreRadius;  // the least fibre radius of curvature
    if (across.yarns >= 2 && !(across.spacing > w))
      json_reader::fail(at, "a crimped start needs the spacing to exceed the yarn width " + num(w) +
                                " mm (side by side, with room for the " + name +
                                " yarns' ramps), got " + num(across.spacing));
    const double least = w + kPi * std::sqrt(H * (vMax + bend));  // (s - w)^2 / (pi^2 H) = v_max + bend
    if (hasRamp(f, warp) && !(across.spacing > least))
      json_reader::fail(at, "a crimped start needs spacing > " + num(least) + " mm (the " + name +
                                " yarns' ramps between " + acrossName + " yarns " + num(w) +
                                " mm wide, crimp height " + num(H) +
                                " mm: radius of curvature (spacing - width)^2/(pi^2 H) above the " +
                                name + " fibres' offset " + num(vMax) + " mm plus " +
                                std::to_string(int(kCrimpBendRadii)) + " fibre radii, " + num(bend) +
                                " mm), got " + num(across.spacing));
  }
}

}  // namespace fibra
