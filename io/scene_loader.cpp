// Scene loader: the top level, materials, fibres, groups, steps and output. Boundary
// conditions, loads, tables, tools and contact are in scene_loader_motion.cpp.
#include "io/scene_loader.h"

#include "io/generators.h"
#include "io/json_reader.h"
#include "io/scene_sections.h"
#include "io/scene_validate.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fibra {
namespace scene_sections {

using namespace json_reader;

MaterialDef readMaterial(const Json& j, const std::string& path) {
  const Fields f(j, path,
                 {"name", "young_modulus", "poisson_ratio", "bending_factor", "torsion_factor",
                  "law"});
  MaterialDef m;
  m.name = f.string("name");
  m.youngModulus = f.number("young_modulus");
  m.poissonRatio = f.number("poisson_ratio", m.poissonRatio);
  m.bendingFactor = f.number("bending_factor", m.bendingFactor);
  m.torsionFactor = f.number("torsion_factor", m.torsionFactor);
  m.law = f.choice("law",
                   {{"saint_venant_kirchhoff", MaterialLaw::SaintVenantKirchhoff},
                    {"neo_hookean", MaterialLaw::NeoHookean}},
                   m.law);
  return m;
}

namespace {

std::vector<Vec3> readPoints(const Fields& f) {
  std::vector<Vec3> points;
  forEachItem(f.at("points"), f.path("points"),
              [&](const Json& p, const std::string& at) { points.push_back(asVec3(p, at)); });
  return points;
}

GeometryDef readGeometry(const Json& j, const std::string& path) {
  GeometryDef g;
  g.kind =
      Fields(j, path,
             {"type", "points", "director", "origin", "axis", "radius", "pitch", "turns", "phase"})
          .choice<GeometryKind>("type", {{"line", GeometryKind::Line},
                                         {"polyline", GeometryKind::Polyline},
                                         {"helix", GeometryKind::Helix}});
  if (g.kind == GeometryKind::Helix) {
    const Fields f(j, path, {"type", "origin", "axis", "radius", "pitch", "turns", "phase"},
                   "a helix geometry");
    g.origin = f.vec3("origin", g.origin);
    g.axis = f.vec3("axis", g.axis);
    g.helixRadius = f.number("radius");
    g.pitch = f.number("pitch");
    g.turns = f.number("turns");
    g.phase = f.number("phase", g.phase);
    return g;
  }
  const Fields f(j, path, {"type", "points", "director"},
                 g.kind == GeometryKind::Line ? "a line geometry" : "a polyline geometry");
  g.points = readPoints(f);
  g.director = f.vec3("director", g.director);
  return g;
}

BeamIntegration readIntegration(const Json& j, const std::string& path) {
  BeamIntegration r;
  r.section =
      Fields(j, path, {"axial", "section", "rings", "sectors"})
          .choice("section",
                  {{"moments", SectionRule::Moments}, {"quadrature", SectionRule::Quadrature}},
                  r.section);
  const Fields f = r.section == SectionRule::Quadrature
                       ? Fields(j, path, {"axial", "section", "rings", "sectors"})
                       : Fields(j, path, {"axial", "section"}, "section \"moments\"");
  r.axial =
      f.choice("axial", {{"reduced", AxialRule::Reduced}, {"full", AxialRule::Full}}, r.axial);
  r.rings = f.integer("rings", r.rings);
  r.sectors = f.integer("sectors", r.sectors);
  return r;
}

}  // namespace

FibreDef readFibre(const Json& j, const std::string& path) {
  const Fields f(j, path,
                 {"name", "material", "radius", "elements", "order", "geometry", "integration",
                  "class", "levels"});
  FibreDef d;
  d.name = f.string("name");
  d.material = f.string("material");
  d.radius = f.number("radius");
  d.elements = f.integer("elements");
  d.order = f.integer("order", d.order);
  d.geometry = readGeometry(f.at("geometry"), f.path("geometry"));
  if (f.has("integration"))
    d.integration = readIntegration(f.at("integration"), f.path("integration"));
  d.contactClass = f.string("class", d.contactClass);
  if (f.has("levels")) d.levels = readLevels(f.at("levels"), f.path("levels"));
  return d;
}

// A group: nodes of one fibre ("fibre" and "nodes") or a union of other groups ("union").
GroupDef readGroup(const Json& j, const std::string& path) {
  const Fields any(j, path, {"name", "fibre", "nodes", "union"});
  const bool isUnion = any.has("union");
  if (!isUnion && !any.has("fibre") && !any.has("nodes"))
    fail(path, "give either 'fibre' and 'nodes' (nodes of one fibre) or 'union' (names of other "
               "groups)");
  const Fields f = isUnion ? Fields(j, path, {"name", "union"}, "a union group")
                           : Fields(j, path, {"name", "fibre", "nodes"});
  GroupDef g;
  g.name = f.string("name");
  if (isUnion) {
    forEachItem(f.at("union"), f.path("union"), [&](const Json& n, const std::string& at) {
      g.members.push_back(asString(n, at));
    });
    if (g.members.empty()) fail(f.path("union"), "must list at least one group");
    return g;
  }
  g.fibre = f.string("fibre");
  forEachItem(f.at("nodes"), f.path("nodes"),
              [&](const Json& n, const std::string& at) { g.nodes.push_back(asInteger(n, at)); });
  return g;
}

StepDef readStep(const Json& j, const std::string& path) {
  const Fields f(j, path,
                 {"name", "end_time", "increments", "max_iterations", "force_tolerance",
                  "increment_tolerance", "max_cutbacks", "line_search", "predictor", "damping",
                  "damping_from", "output_every", "forced_normals", "friction_factor"});
  StepDef s;
  s.name = f.string("name", s.name);
  s.endTime = f.number("end_time", s.endTime);
  s.increments = f.integer("increments", s.increments);
  s.maxIterations = f.integer("max_iterations", s.maxIterations);
  s.forceTolerance = f.number("force_tolerance", s.forceTolerance);
  s.incrementTolerance = f.number("increment_tolerance", s.incrementTolerance);
  s.maxCutbacks = f.integer("max_cutbacks", s.maxCutbacks);
  s.lineSearch = f.boolean("line_search", s.lineSearch);
  s.predictor = f.boolean("predictor", s.predictor);
  s.damping = f.number("damping", s.damping);
  s.dampingFrom = f.choice("damping_from",
                           {{"start", DampingFrom::Start}, {"failure", DampingFrom::Failure}},
                           s.dampingFrom);
  s.outputEvery = f.integer("output_every", s.outputEvery);
  s.frictionFactor = f.number("friction_factor", s.frictionFactor);
  if (f.has("forced_normals"))
    readForcedNormals(f.at("forced_normals"), f.path("forced_normals"), s);
  return s;
}

// {"x": COLUMN, "y": COLUMN or [COLUMN, ...], "file": "NAME.png", "title": T}
PlotDef readPlot(const Json& j, const std::string& path) {
  const Fields f(j, path, {"x", "y", "file", "title"});
  PlotDef p{f.string("x"), {}, f.string("file"), f.string("title", "")};
  if (f.at("y").is_string())
    p.y.push_back(f.string("y"));
  else
    forEachItem(f.at("y"), f.path("y"), [&](const Json& y, const std::string& at) {
      p.y.push_back(asString(y, at));
    });
  return p;
}

namespace {

// A probe's node: an index within the fibre, or "end", the fibre's last node (order x elements,
// whatever the mesh). An unknown fibre gives -1, which validation reports with the fibre's name.
int probeNode(const Fields& pf, const std::vector<FibreDef>& fibres) {
  if (!pf.at("node").is_string()) return pf.integer("node");
  const std::string node = pf.string("node");
  if (node != "end")
    fail(pf.path("node"), "expected a node index or \"end\", got \"" + shown(node) + "\"");
  const std::string fibre = pf.string("fibre");
  for (const FibreDef& f : fibres)
    if (f.name == fibre) return f.order * f.elements;
  return -1;
}

}  // namespace

OutputDef readOutput(const Json& j, const std::string& path,
                     const std::vector<FibreDef>& fibres) {
  const Fields f(j, path,
                 {"vtu", "vtu_format", "history", "final_state", "checkpoint", "moment_point",
                  "probes", "plots"});
  OutputDef o;
  o.vtu = f.boolean("vtu", o.vtu);
  o.vtuEncoding = f.choice("vtu_format",
                           {{"binary", VtuEncoding::Binary}, {"ascii", VtuEncoding::Ascii}},
                           o.vtuEncoding);
  o.history = f.boolean("history", o.history);
  o.finalState = f.boolean("final_state", o.finalState);
  o.checkpoint = f.boolean("checkpoint", o.checkpoint);
  o.momentPoint = f.vec3("moment_point", o.momentPoint);
  if (f.has("probes"))
    forEachItem(f.at("probes"), f.path("probes"), [&](const Json& p, const std::string& at) {
      const Fields pf(p, at, {"name", "fibre", "node"});
      o.probes.push_back({pf.string("name"), pf.string("fibre"), probeNode(pf, fibres)});
    });
  if (f.has("plots"))
    forEachItem(f.at("plots"), f.path("plots"), [&](const Json& p, const std::string& at) {
      o.plots.push_back(readPlot(p, at));
    });
  return o;
}

}  // namespace scene_sections

namespace {

using namespace json_reader;
using namespace scene_sections;

template <class Def, class Read>
std::vector<Def> readList(const Fields& f, const char* key, Read read) {
  std::vector<Def> defs;
  if (f.has(key))
    forEachItem(f.at(key), f.path(key),
                [&](const Json& j, const std::string& at) { defs.push_back(read(j, at)); });
  return defs;
}

// Lists that a scene cannot do without.
void requireItems(const Fields& f, const char* key) {
  if (f.at(key).is_array() && f.at(key).empty()) fail(f.path(key), "must list at least one entry");
}

SceneDef readScene(const Json& root) {
  const Fields f(
      root, "",
      {"description", "units", "materials", "fibres", "groups", "tables", "boundary_conditions",
       "loads", "steps", "contact", "tools", "stabilisation", "solver", "output",
       "generators"});  // expanded and removed before (named here for the suggestion)
  f.string("description", "");
  SceneDef s;
  s.units = f.string("units");
  for (const char* key : {"materials", "fibres", "steps"}) requireItems(f, key);
  const Tables tables = f.has("tables") ? readTables(f.at("tables"), "tables") : Tables{};
  s.materials = readList<MaterialDef>(f, "materials", readMaterial);
  s.fibres = readList<FibreDef>(f, "fibres", readFibre);
  s.groups = readList<GroupDef>(f, "groups", readGroup);
  s.bcs = readList<BcDef>(f, "boundary_conditions", [&](const Json& j, const std::string& at) {
    return readBc(j, at, tables);
  });
  s.loads = readList<LoadDef>(
      f, "loads", [&](const Json& j, const std::string& at) { return readLoad(j, at, tables); });
  s.steps = readList<StepDef>(f, "steps", readStep);
  if (f.has("contact")) s.contact = readContact(f.at("contact"), "contact");
  s.tools = readList<ToolDef>(
      f, "tools", [&](const Json& j, const std::string& at) { return readTool(j, at, tables); });
  if (f.has("stabilisation"))
    s.stabilisation = readStabilisation(f.at("stabilisation"), "stabilisation");
  if (f.has("solver")) s.solver = readSolver(f.at("solver"), "solver");
  if (f.has("output")) s.output = readOutput(f.at("output"), "output", s.fibres);
  return s;
}

// The scene text parsed, its generators expanded (io/generators.h), read and checked; errors
// name the file.
struct Expanded {
  Json root;  // the plain scene, generators expanded
  SceneDef scene;
};

Expanded expandedScene(const std::string& text, const std::string& displayName) {
  try {
    Expanded out{expandGenerators(json_reader::parse(text)), {}};
    out.scene = readScene(out.root);
    validateScene(out.scene);
    return out;
  } catch (const SceneError& e) {
    throw SceneError(displayName + ": " + e.what());
  }
}

std::string readSceneFile(const std::string& path) {
  if (std::filesystem::is_directory(path))
    throw SceneError(path + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  return text.str();
}

}  // namespace

SceneDef loadSceneFromString(const std::string& text, const std::string& displayName) {
  return expandedScene(text, displayName).scene;
}

SceneDef loadScene(const std::string& path) {
  return loadSceneFromString(readSceneFile(path), path);
}

std::string expandSceneFromString(const std::string& text, const std::string& displayName) {
  return json_reader::readableDump(expandedScene(text, displayName).root);
}

std::string expandScene(const std::string& path) {
  return expandSceneFromString(readSceneFile(path), path);
}

}  // namespace fibra
