// The run outputs as a library (io/outputs.h): binary VTU read back equal to the ASCII writer's,
// the tools' surfaces in part 2 of every frame and following their motion, and a re-run that
// replaces only fibra's own files.
#include "engine/world.h"
#include "io/outputs.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"
#include "systems/tool_geometry.h"
#include "vtu_reader.h"

#include <doctest/doctest.h>

#include <regex>

using namespace fibra;
using namespace fibra::test;

namespace {

// The world of a sample scene, on one thread, after `increments` converged increments.
World sampleWorld(const std::string& name, int increments) {
  WorldDef def;
  def.threads = 1;
  World world(loadScene(sourcePath("samples/" + name + ".json")), def);
  for (int i = 0; i < increments; ++i) REQUIRE(world.step().status == StepStatus::Converged);
  return world;
}

std::vector<std::string> vtuFiles(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".vtu") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Every tool point lies on the tool's surface at `time` (moved by its motion).
void checkOnToolSurfaces(const World& world, const VtuArrays& a, double time) {
  const ToolStore& tools = world.tools();
  const std::vector<double>& points = a.at("Points/");
  const std::vector<double>& connectivity = a.at("Cells/connectivity");
  const std::vector<double>& offsets = a.at("Cells/offsets");
  const std::vector<double>& tool = a.at("CellData/tool");
  REQUIRE(tool.size() == offsets.size());
  for (size_t c = 0; c < offsets.size(); ++c) {
    const Index t = Index(tool[c]);
    REQUIRE(t < tools.size());
    const RigidMotion m = toolMotion(tools, t, time);
    for (size_t k = c == 0 ? 0 : size_t(offsets[c - 1]); k < size_t(offsets[c]); ++k) {
      const size_t p = size_t(connectivity[k]);
      const Vec3 x(points[3 * p], points[3 * p + 1], points[3 * p + 2]);
      CHECK(std::abs(closestSurfacePoint(tools, t, m, x).distance) < 1e-9);
    }
  }
}

}  // namespace

TEST_CASE("binary VTU: zlib-compressed appended arrays read back equal to the ASCII writer's") {
  // The roller scene after three increments has fibres, contact elements and a tool: every
  // array of every file of a frame, written both ways, holds the same values.
  const World world = sampleWorld("roller_drag", 3);
  TempDir dir("vtu_binary");
  Outputs binary((dir.path() / "binary").string(), world, VtuEncoding::Binary);
  Outputs ascii((dir.path() / "ascii").string(), world, VtuEncoding::Ascii);
  const std::vector<std::string> files = vtuFiles(dir.path() / "binary");
  REQUIRE(files == std::vector<std::string>{"result_0000.vtu", "result_contacts_0000.vtu",
                                            "result_tools_0000.vtu"});
  REQUIRE(vtuFiles(dir.path() / "ascii") == files);
  for (const std::string& f : files) {
    CAPTURE(f);
    const std::string b = readFile((dir.path() / "binary" / f).string()),
                      t = readFile((dir.path() / "ascii" / f).string());
    CHECK(b.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
    CHECK(b.find("format=\"ascii\"") == std::string::npos);
    CHECK(t.find("format=\"appended\"") == std::string::npos);
    const VtuArrays fromBinary = readVtuArrays(b), fromAscii = readVtuArrays(t);
    CHECK(fromBinary.size() >= 4);
    CHECK(fromBinary == fromAscii);  // the same bits: ASCII numbers are shortest round-trip
  }
  const VtuArrays fibres = readVtuArrays(readFile((dir.path() / "binary" / files[0]).string()));
  CHECK(fibres.at("Points/").size() == 3 * size_t(world.fibres().nodes()) * 13);
  CHECK(fibres.at("Points/")[0] == world.fibres().q[0]);
}

TEST_CASE("tool VTU: the roller as a cylinder surface and the plates as patches, moving") {
  SUBCASE("roller: a cylinder of the tool's radius around its axis, covering the fibre") {
    const World world = sampleWorld("roller_drag", 1);
    TempDir dir("vtu_roller");
    Outputs out(dir.path().string(), world);
    const VtuArrays a = readVtuArrays(readFile(dir / "result_tools_0000.vtu"));
    CHECK(a.at("CellData/tool").size() == 32);  // VtuDef::toolSides quads
    CHECK(a.at("CellData/kind") == std::vector<double>(32, 1.0));
    checkOnToolSurfaces(world, a, world.time());
    // The cylinder spans the fibre's extent along the axis (y), with the margin.
    double lo = 1e300, hi = -1e300, fibreLo = 1e300, fibreHi = -1e300;
    for (size_t i = 1; i < a.at("Points/").size(); i += 3) {
      lo = std::min(lo, a.at("Points/")[i]);
      hi = std::max(hi, a.at("Points/")[i]);
    }
    for (Index n = 0; n < world.fibres().nodes(); ++n) {
      fibreLo = std::min(fibreLo, world.fibres().q[9 * n + 1]);
      fibreHi = std::max(fibreHi, world.fibres().q[9 * n + 1]);
    }
    CHECK(lo < fibreLo - 0.99);
    CHECK(hi > fibreHi + 0.99);
    CHECK(readFile(dir / "result.pvd").find("part=\"2\" file=\"result_tools_0000.vtu\"") !=
          std::string::npos);
  }
  SUBCASE("bundle: two plane patches, the top one moved with its motion in a later frame") {
    World world = sampleWorld("bundle_squeeze", 0);
    TempDir dir("vtu_plates");
    Outputs out(dir.path().string(), world);
    const VtuArrays first = readVtuArrays(readFile(dir / "result_tools_0000.vtu"));
    CHECK(first.at("CellData/tool") == std::vector<double>{0, 1});
    CHECK(first.at("CellData/kind") == std::vector<double>{0, 0});
    checkOnToolSurfaces(world, first, 0);
    for (int i = 0; i < 2; ++i) {
      const StepReport r = world.step();
      REQUIRE(r.status == StepStatus::Converged);
      out.increment(world, r);
    }
    REQUIRE(out.frames() == 3);
    const VtuArrays later = readVtuArrays(readFile(dir / "result_tools_0002.vtu"));
    checkOnToolSurfaces(world, later, world.time());
    const Vec3 shift = toolMotion(world.tools(), 1, world.time())(Vec3::Zero()) -
                       toolMotion(world.tools(), 1, 0)(Vec3::Zero());
    CHECK(shift.norm() > 0);  // the top plate moved ...
    CHECK(later.at("Points/")[4 * 3 + 2] - first.at("Points/")[4 * 3 + 2] ==
          doctest::Approx(shift.z()).scale(0));  // ... and its patch (points 4-7) with it
    out.finish(world);
  }
}

TEST_CASE("clearOutputs removes a previous run's files and nothing else") {
  TempDir dir("clear_outputs");
  fs::create_directories(dir.path());
  const std::vector<std::string> own{"result.pvd",          "result_0000.vtu",
                                     "result_0012.vtu",     "result_contacts_0003.vtu",
                                     "result_tools_0003.vtu", "history.csv",
                                     "history.csv.part",    "final_state.csv"},
                                 other{"notes.txt", "result_final.vtu", "history.csv.bak",
                                       "trace.json"};
  for (const auto& n : own) writeFile(dir / n, "x");
  for (const auto& n : other) writeFile(dir / n, "x");
  CHECK(clearOutputs(dir.path().string()) == int(own.size()));
  for (const auto& n : own) CHECK_FALSE(fs::exists(dir / n));
  for (const auto& n : other) CHECK(fs::exists(dir / n));
  CHECK(clearOutputs((dir.path() / "missing").string()) == 0);
}
