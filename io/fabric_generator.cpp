// The woven-fabric generator: spec reading (pattern, warp and weft, start), the flat layout, the
// level tables and the scene entries they expand into, flat or crimped (io/fabric_crimp.cpp; the
// formulas are in fabric_generator.h).
#include "io/fabric_generator.h"

#include "io/generator_fields.h"
#include "io/generators.h"
#include "io/yarn_generator.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace fibra {
namespace {

using namespace generator_fields;

// A user matrix of 0/1: rectangular, at least 1 x 1.
WeavePattern readMatrix(const Json& j, const std::string& path) {
  WeavePattern p;
  json_reader::forEachItem(j, path, [&](const Json& row, const std::string& rowPath) {
    std::vector<int> cells;
    json_reader::forEachItem(row, rowPath, [&](const Json& cell, const std::string& at) {
      const int v = json_reader::asInteger(cell, at);
      if (v != 0 && v != 1) json_reader::fail(at, "must be 0 or 1, got " + std::to_string(v));
      cells.push_back(v);
    });
    if (cells.empty()) json_reader::fail(rowPath, "must hold at least one 0 or 1");
    if (!p.empty() && cells.size() != p[0].size())
      json_reader::fail(rowPath, "has " + std::to_string(cells.size()) + " entries, row 0 has " +
                                     std::to_string(p[0].size()) +
                                     " (the matrix must be rectangular)");
    p.push_back(cells);
  });
  if (p.empty()) json_reader::fail(path, "must hold at least one row");
  return p;
}

// A named weave: "plain", "twill" (2/2), "satin" (5, step 2), or {"weave": ..., parameters}.
WeavePattern readNamed(const Json& j, const std::string& path) {
  const bool isObject = j.is_object();
  const Json spec = isObject ? j : Json{{"weave", j}};
  const Fields f(spec, path, {"weave", "over", "under", "repeat", "step"}, "a named weave");
  const std::string weave = isObject ? f.string("weave") : json_reader::asString(j, path);
  const std::string at = isObject ? f.path("weave") : path;
  if (weave == "plain") return plainWeave();
  if (weave == "twill")
    return twillWeave(integerIn(f, "over", 2, 1, 100), integerIn(f, "under", 2, 1, 100));
  if (weave == "satin") {
    const int n = integerIn(f, "repeat", 5, 5, 100), s = integerIn(f, "step", 2, 2, n - 2);
    if (std::gcd(n, s) != 1)
      bad(f, "step", "must have no common factor with repeat " + std::to_string(n) + ", got " +
                         std::to_string(s));
    return satinWeave(n, s);
  }
  json_reader::fail(at, "unknown weave \"" + json_reader::shown(weave) +
                            "\" (expected one of: plain, twill, satin, or a matrix of 0/1)");
}

WeavePattern readPattern(const Json& j, const std::string& path) {
  return j.is_array() ? readMatrix(j, path) : readNamed(j, path);
}

double halfWidth(const WeaveDirection& d) {  // of a yarn's section across it, fibre surface, mm
  double w = 0;
  for (const auto& site : hexagonalLayout(d.fibresPerYarn, 2 * d.fibreRadius + d.gap))
    w = std::max(w, std::abs(site[0]));
  return w + d.fibreRadius;
}

WeaveDirection readDirection(const Fields& parent, const char* key) {
  const Fields f(parent.at(key), parent.path(key),
                 {"yarns", "spacing", "fibres_per_yarn", "fibre_radius", "gap", "material",
                  "elements", "order", "length"});
  WeaveDirection d;
  d.yarns = integerIn(f, "yarns", 0, 1, 10000);
  d.fibresPerYarn = integerIn(f, "fibres_per_yarn", 0, 1, 100000);
  d.fibreRadius = positive(f, "fibre_radius");
  d.spacing = positive(f, "spacing");
  if (d.spacing < 2 * d.fibreRadius)
    bad(f, "spacing", "must be at least 2 fibre radii (" + num(2 * d.fibreRadius) + " mm), got " +
                          num(d.spacing));
  d.gap = f.number("gap", d.gap);
  if (!(d.gap >= 0 && std::isfinite(d.gap))) bad(f, "gap", "must be >= 0, got " + num(d.gap));
  d.material = f.string("material");
  d.elements = integerIn(f, "elements", 0, 1, 100000);
  checkElementCount(f, double(d.yarns) * d.fibresPerYarn, d.elements);
  d.order = f.integer("order", d.order);
  if (d.order != 1 && d.order != 2)
    bad(f, "order", "must be 1 or 2, got " + std::to_string(d.order));
  if (f.has("length")) d.length = positive(f, "length");
  return d;
}

// The default length (the other direction's yarns plus one of its spacings at each end, at least
// their span plus one spacing), or a
// check that the given one covers every crossing.
void fillLength(const Fields& parent, const char* key, WeaveDirection& d,
                const WeaveDirection& across) {
  const double span = (across.yarns - 1) * across.spacing + 2 * halfWidth(across);
  if (d.length == 0) {
    d.length = std::max((across.yarns + 1) * across.spacing, span + across.spacing);
    return;
  }
  if (d.length <= span)
    json_reader::fail(parent.path(key) + ".length",
                      "must exceed the span of the crossing yarns (" + num(span) + " mm), got " +
                          num(d.length));
}

}  // namespace

WeavePattern plainWeave() { return {{1, 0}, {0, 1}}; }

WeavePattern twillWeave(int over, int under) {
  const int n = over + under;
  WeavePattern p(n, std::vector<int>(n));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) p[r][c] = ((c - r) % n + n) % n < over ? 1 : 0;
  return p;
}

WeavePattern satinWeave(int repeat, int step) {
  WeavePattern p(repeat, std::vector<int>(repeat, 0));
  for (int r = 0; r < repeat; ++r) p[r][(r * step) % repeat] = 1;
  return p;
}

FabricDef readFabric(const Json& spec, const std::string& path) {
  const Fields f(spec, path, {"type", "name", "pattern", "warp", "weft", "start"},
                 "a woven_fabric generator");
  FabricDef fab;
  fab.name = f.string("name");
  checkName(f, fab.name);
  fab.pattern = readPattern(f.at("pattern"), f.path("pattern"));
  fab.warp = readDirection(f, "warp");
  fab.weft = readDirection(f, "weft");
  fillLength(f, "warp", fab.warp, fab.weft);
  fillLength(f, "weft", fab.weft, fab.warp);
  fab.start = f.choice("start", {{"flat", FabricStart::Flat}, {"crimped", FabricStart::Crimped}},
                       FabricStart::Flat);
  if (fab.start == FabricStart::Crimped) checkCrimp(fab, path);
  return fab;
}

int warpOver(const FabricDef& f, int r, int c) {
  const WeavePattern& p = f.pattern;
  return p[size_t(r) % p.size()][size_t(c) % p[0].size()];
}

double yarnAxisPosition(const WeaveDirection& d, int k) {
  return (k - 0.5 * (d.yarns - 1)) * d.spacing;
}

std::array<Vec3, 2> fabricFibreEnds(const FabricDef& f, bool warp, int c, int k) {
  const WeaveDirection& d = warp ? f.warp : f.weft;
  const auto site = hexagonalLayout(d.fibresPerYarn, 2 * d.fibreRadius + d.gap)[size_t(k)];
  const auto exact = [&](double v) { return std::abs(v) < 1e-12 * d.fibreRadius ? 0.0 : v; };
  const double across = yarnAxisPosition(d, c) + exact(site[0]), z = exact(site[1]);
  const double half = d.length / 2;  // a row's round-off (sin pi) snapped to z = 0
  if (warp) return {Vec3(-half, across, z), Vec3(half, across, z)};
  return {Vec3(across, -half, z), Vec3(across, half, z)};
}

std::vector<std::array<double, 2>> warpLevels(const FabricDef& f, int c) {
  std::vector<std::array<double, 2>> pieces;
  const double start = -f.warp.length / 2;  // x of the warp fibres' start
  for (int r = 0; r < f.weft.yarns; ++r) {
    const double level = warpOver(f, r, c) ? 1 : -1;
    const double from =
        r == 0 ? 0 : 0.5 * (yarnAxisPosition(f.weft, r - 1) + yarnAxisPosition(f.weft, r)) - start;
    if (pieces.empty() || pieces.back()[1] != level) pieces.push_back({from, level});
  }
  return pieces;
}

namespace {

std::string yarnName(const FabricDef& f, bool warp, int c) {
  return f.name + (warp ? ".warp" : ".weft") + std::to_string(c);
}

Json vec(const Vec3& v) { return Json::array({v(0), v(1), v(2)}); }

Json levelsJson(const std::vector<std::array<double, 2>>& pieces) {
  Json levels = Json::array();
  for (const auto& piece : pieces) levels.push_back({piece[0], piece[1]});
  return levels;
}

// The flat start's line, or the crimped start's polyline; director +z at the start either way.
Json geometryJson(const std::string& type, const std::vector<Vec3>& points) {
  Json pts = Json::array();
  for (const Vec3& p : points) pts.push_back(vec(p));
  return {{"type", type}, {"points", pts}, {"director", vec(Vec3::UnitZ())}};
}

Json fibreJson(const FabricDef& f, bool warp, int c, int k) {
  const WeaveDirection& d = warp ? f.warp : f.weft;
  Json levels = 0, geometry;
  if (f.start == FabricStart::Flat) {
    const auto ends = fabricFibreEnds(f, warp, c, k);
    if (warp) levels = levelsJson(warpLevels(f, c));
    geometry = geometryJson("line", {ends[0], ends[1]});
  } else {
    const std::vector<Vec3> points = crimpedCentreline(f, warp, c, k);
    if (warp) levels = levelsJson(crimpedWarpLevels(f, c, points));
    geometry = geometryJson("polyline", points);
  }
  return {{"name", yarnName(f, warp, c) + ".f" + std::to_string(k)},
          {"material", d.material},
          {"radius", d.fibreRadius},
          {"elements", d.elements},
          {"order", d.order},
          {"class", f.name + (warp ? ".warp" : ".weft")},
          {"levels", levels},
          {"geometry", geometry}};
}

Json unionJson(const std::string& name, const std::vector<std::string>& members) {
  return {{"name", name}, {"union", members}};
}

// The groups of one direction: every yarn's ends, then the direction's ends as wholes.
void directionGroups(const FabricDef& f, bool warp, Json& groups) {
  const WeaveDirection& d = warp ? f.warp : f.weft;
  const std::string dir = f.name + (warp ? ".warp" : ".weft");
  for (const char* end : {".start", ".end"}) {
    std::vector<std::string> yarnEnds;
    for (int c = 0; c < d.yarns; ++c) {
      std::vector<std::string> fibreEnds;
      for (int k = 0; k < d.fibresPerYarn; ++k)
        fibreEnds.push_back(yarnName(f, warp, c) + ".f" + std::to_string(k) + end);
      groups.push_back(unionJson(yarnName(f, warp, c) + end, fibreEnds));
      yarnEnds.push_back(yarnName(f, warp, c) + end);
    }
    groups.push_back(unionJson(dir + end, yarnEnds));
  }
}

}  // namespace

void expandWovenFabric(const Json& spec, const std::string& path, Json& scene) {
  const FabricDef f = readFabric(spec, path);
  Json& fibres = sceneList(scene, "fibres");
  for (bool warp : {true, false}) {
    const WeaveDirection& d = warp ? f.warp : f.weft;
    for (int c = 0; c < d.yarns; ++c)
      for (int k = 0; k < d.fibresPerYarn; ++k) fibres.push_back(fibreJson(f, warp, c, k));
  }
  Json& groups = sceneList(scene, "groups");
  directionGroups(f, true, groups);
  directionGroups(f, false, groups);
  // The four edges: warp yarns run along x (start at x min), weft yarns along y.
  groups.push_back(unionJson(f.name + ".edge.xmin", {f.name + ".warp.start"}));
  groups.push_back(unionJson(f.name + ".edge.xmax", {f.name + ".warp.end"}));
  groups.push_back(unionJson(f.name + ".edge.ymin", {f.name + ".weft.start"}));
  groups.push_back(unionJson(f.name + ".edge.ymax", {f.name + ".weft.end"}));
}

}  // namespace fibra
