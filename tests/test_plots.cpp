// Pictures made by fibra (io/plot.h, io/section_cut.h, `fibra plot`, `fibra section`, the
// scene's output.plots): history column lookup and its errors, units on axis labels, the
// gnuplot script, the cut geometry of fibre sections (independent of gnuplot), and, where
// gnuplot is installed, PNGs actually drawn from a tiny run.
#include "io/plot.h"
#include "io/section_cut.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

using namespace fibra;
using namespace fibra::test;
using Json = nlohmann::json;

namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A straight fibre of `nodes` nodes through `centre` along unit `t`, directors g1, g2 (not
// necessarily unit: a deformed section), radius R, nodes `spacing` mm apart, centred.
FibreFrame straightFibre(const Vec3& centre, const Vec3& t, const Vec3& g1, const Vec3& g2,
                         double R, int nodes = 7, double spacing = 0.5) {
  FibreFrame f;
  f.fibres.emplace_back();
  for (int i = 0; i < nodes; ++i) {
    f.x0.push_back(centre + (i - 0.5 * (nodes - 1) + 0.3) * spacing * t);  // 0.3: no node on it
    f.g1.push_back(g1);
    f.g2.push_back(g2);
    f.radius.push_back(R);
    f.fibres.back().push_back(Index(i));
  }
  return f;
}

// Twice the signed area of a closed polygon in the (a, b) coordinates of its points.
double shoelace(const std::vector<Vec3>& p, int a, int b) {
  double twice = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const Vec3& u = p[k];
    const Vec3& v = p[(k + 1) % p.size()];
    twice += u[a] * v[b] - v[a] * u[b];
  }
  return 0.5 * twice;
}

bool isPng(const std::string& path) {
  const std::string bytes = readFile(path);
  return bytes.size() > 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// A tiny run: the cantilever sample in 3 increments, `output` added to its output section.
std::string tinyScene(const TempDir& dir, const Json& output) {
  Json s = Json::parse(readFile(sourcePath("samples/cantilever.json")), nullptr, true, true);
  s["steps"][0]["increments"] = 3;
  s["output"].update(output);  // the sample's probe "tip" stays
  fs::create_directories(dir.path());
  const std::string path = dir / "scene.json";
  writeFile(path, s.dump());
  return path;
}

const std::vector<std::string> kColumns = {"time", "iterations", "reaction.beam.start.fy",
                                           "probe.tip.y", "energy.strain"};

}  // namespace

TEST_CASE("plot: an unknown history column is an error naming the file and the known columns") {
  TempDir dir("plot_columns");
  fs::create_directories(dir.path());
  writeFile(dir / "history.csv", "time,iterations,probe.tip.y\n0.5,3,-1\n");
  const std::vector<std::string> columns = readHistoryColumns(dir / "history.csv");
  CHECK(columns == std::vector<std::string>{"time", "iterations", "probe.tip.y"});
  CHECK(findColumn(columns, "probe.tip.y", "h.csv", "y") == 2);
  const std::string e =
      messageOf([&] { findColumn(columns, "probe.tip.z", dir / "history.csv", "y"); });
  CHECK(contains(e, dir / "history.csv"));
  CHECK(contains(e, "y: unknown column 'probe.tip.z'"));
  CHECK(contains(e, "did you mean 'probe.tip.y'?"));
  CHECK(contains(e, "the columns are: time, iterations, probe.tip.y"));
  CHECK_THROWS_AS(findColumn(columns, "x", "h.csv", "x"), PlotInputError);
  // No history, and a history without rows.
  const std::string missing = messageOf([&] { readHistoryColumns(dir / "none.csv"); });
  CHECK(contains(missing, dir / "none.csv"));
  CHECK(contains(missing, "cannot read the history"));
  writeFile(dir / "empty.csv", "time,iterations\n");
  CHECK(contains(messageOf([&] { readHistoryColumns(dir / "empty.csv"); }), "has no row"));
  CHECK(readHistoryColumns(dir / "empty.csv", false).size() == 2);
}

TEST_CASE("plot: axis labels carry the units of known columns and none for unknown ones") {
  CHECK(columnUnit("reaction.beam.end.fy") == "N");
  CHECK(columnUnit("reaction.B#2.mz") == "N mm");
  CHECK(columnUnit("tool.top.fy") == "N");
  CHECK(columnUnit("tool.top.uy") == "mm");
  CHECK(columnUnit("probe.tip.z") == "mm");
  CHECK(columnUnit("energy.friction") == "N mm");
  CHECK(columnUnit("contact.max_penetration") == "mm");
  CHECK(columnUnit("contact.max_overlap") == "mm");
  CHECK(columnUnit("wall_s") == "s");
  for (const char* none : {"time", "iterations", "load_factor", "residual", "contact.elements",
                           "contact.max_penetration_ratio", "viscous_force", "custom.fy",
                           "probe.tip.speed"})
    CHECK_MESSAGE(columnUnit(none).empty(), none);
  CHECK(axisLabel("time") == "time");
  CHECK(axisLabel("probe.tip.y") == "probe.tip.y (mm)");
  CHECK(axisLabel(std::vector<std::string>{"tool.a.fy", "tool.b.fy"}) ==
        "tool.a.fy, tool.b.fy (N)");
  CHECK(axisLabel(std::vector<std::string>{"tool.a.fy", "probe.p.x", "iterations"}) ==
        "tool.a.fy (N), probe.p.x (mm), iterations");
}

TEST_CASE("plot: the gnuplot script quotes user strings and draws the chosen columns") {
  CHECK(gnuplotString("it's") == "'it''s'");
  CHECK(gnuplotString("a\nb `x` $y") == "'a b `x` $y'");
  const CurvePlot p{"probe.tip.y", {"reaction.beam.start.fy", "energy.strain"}, "Bob's beam",
                    "f.png"};
  const std::string s = curveScript(p, kColumns, "../run dir/history.csv", "f.png");
  CHECK(contains(s, "set output 'f.png'\n"));
  CHECK(contains(s, "set datafile separator ','\n"));
  CHECK(contains(s, "set terminal pngcairo size 900,600 noenhanced"));
  CHECK(contains(s, "set terminal png size 900,600 noenhanced"));
  CHECK(contains(s, "set title 'Bob''s beam'\n"));
  CHECK(contains(s, "set xlabel 'probe.tip.y (mm)'\n"));
  CHECK(contains(s, "set ylabel 'reaction.beam.start.fy (N), energy.strain (N mm)'\n"));
  CHECK(contains(s, "plot '../run dir/history.csv' skip 1 using 4:3 with linespoints pt 7 "
                    "ps 0.5 title 'reaction.beam.start.fy'"));
  CHECK(contains(s, "     '' skip 1 using 4:5 with linespoints pt 7 ps 0.5 title "
                    "'energy.strain'\n"));
  CHECK(contains(s, "set key below noenhanced\n"));
  // A sum of columns: one curve of their sum, labelled with their shared unit.
  CHECK(columnTerms("a+b+c") == std::vector<std::string>{"a", "b", "c"});
  CHECK(columnTerms("a+") == std::vector<std::string>{"a", ""});
  CHECK(columnUnit("reaction.a.fy+reaction.b.fy") == "N");
  CHECK(columnUnit("reaction.a.fy+probe.p.y").empty());
  const CurvePlot sum{"time", {"reaction.beam.start.fy+probe.tip.y+iterations"}, "", "s.png"};
  CHECK(contains(curveScript(sum, kColumns, "h.csv", "s.png"),
                 "using 1:(column(3)+column(4)+column(2)) with"));
  const CurvePlot untitled{"time", {"iterations"}, "", "i.png"};
  CHECK(!contains(curveScript(untitled, kColumns, "history.csv", "i.png"), "set title"));
  CHECK_THROWS_AS(curveScript(CurvePlot{"time", {"nope"}, "", "x.png"}, kColumns, "h", "x.png"),
                  PlotInputError);
}

TEST_CASE("section: the script draws outlines and tools with equal scales in the box") {
  const SectionView view{{-1, -2}, {1, 2}, true};
  const std::string s = sectionScript(CutPlane{0, 0.5}, "cut.dat", "cut.png", "a 'cut'", view);
  CHECK(contains(s, "set size ratio -1\n"));
  CHECK(contains(s, "set title 'a ''cut'''\n"));
  CHECK(contains(s, "set xlabel 'y (mm)'\nset ylabel 'z (mm)'\n"));
  CHECK(contains(s, "set xrange [-1:1]\nset yrange [-2:2]\n"));
  CHECK(contains(s, "plot 'cut.dat' index 0 using 1:2 with filledcurves closed"));
  CHECK(contains(s, "'' index 1 using 1:2 with lines"));
  CHECK(!contains(sectionScript(CutPlane{}, "c.dat", "c.png", "", SectionView{}), "index 1"));
}

TEST_CASE("section: a round fibre normal to the plane is cut in a circle of radius R") {
  const double R = 0.1;
  const FibreFrame f = straightFibre({1, 2, 3}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, R);
  const std::vector<SectionOutline> cut = cutSections(f, CutPlane{2, 3.0}, 36);
  REQUIRE(cut.size() == 1);
  CHECK(cut[0].fibre == 0);
  CHECK(cut[0].centre.isApprox(Vec3(1, 2, 3)));
  REQUIRE(cut[0].points.size() == 36);
  for (const Vec3& p : cut[0].points) {
    CHECK(p.z() == 3.0);
    CHECK((p - Vec3(1, 2, 3)).norm() == doctest::Approx(R).epsilon(1e-12));
  }
  CHECK(planeAxes(2) == std::array<int, 2>{0, 1});
}

TEST_CASE("section: a fibre crossing the plane at an angle is cut in the known ellipse") {
  // Along t = (sin a, 0, cos a) with g1 = (cos a, 0, -sin a), g2 = (0, 1, 0): the plane z = 0
  // cuts an ellipse of semi-axes R / cos a along x and R along y, area pi R^2 / cos a.
  const double R = 0.05, a = 0.6;
  const Vec3 t(std::sin(a), 0, std::cos(a)), g1(std::cos(a), 0, -std::sin(a)), g2(0, 1, 0);
  const int sides = 64;
  const std::vector<SectionOutline> cut =
      cutSections(straightFibre(Vec3::Zero(), t, g1, g2, R), CutPlane{2, 0.0}, sides);
  REQUIRE(cut.size() == 1);
  REQUIRE(cut[0].points.size() == size_t(sides));
  const double ax = R / std::cos(a), ay = R;
  double widest = 0;
  for (const Vec3& p : cut[0].points) {
    CHECK(std::pow(p.x() / ax, 2) + std::pow(p.y() / ay, 2) == doctest::Approx(1).epsilon(1e-12));
    widest = std::max(widest, std::abs(p.x()));
  }
  CHECK(widest == doctest::Approx(ax).epsilon(1e-12));  // phi = 0 lies on the long axis
  // The polygon of `sides` points at equal phi on an ellipse: (n/2) sin(2 pi/n) ax ay.
  const double polygon = 0.5 * sides * std::sin(2 * std::numbers::pi / sides) * ax * ay;
  CHECK(std::abs(shoelace(cut[0].points, 0, 1)) == doctest::Approx(polygon).epsilon(1e-12));
}

TEST_CASE("section: a flattened section shows as an ellipse of its directors' lengths") {
  const double R = 0.1;
  const FibreFrame f = straightFibre({0, 0, 0}, {1, 0, 0}, {0, 1.5, 0}, {0, 0, 0.6}, R);
  const std::vector<SectionOutline> cut = cutSections(f, CutPlane{0, 0.0}, 40);
  REQUIRE(cut.size() == 1);
  for (const Vec3& p : cut[0].points)
    CHECK(std::pow(p.y() / (1.5 * R), 2) + std::pow(p.z() / (0.6 * R), 2) ==
          doctest::Approx(1).epsilon(1e-12));
}

TEST_CASE("section: fibres that do not reach the plane have no section, a bent one has two") {
  const FibreFrame f = straightFibre({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 0.1);
  CHECK(cutSections(f, CutPlane{2, 10.0}).empty());  // beyond the fibre's end
  CHECK(cutSections(f, CutPlane{0, 0.5}).empty());   // beside it
  // A U: up along z at x = 0, across, down at x = 1; the plane z = 1 cuts both legs.
  FibreFrame u;
  u.fibres.emplace_back();
  const std::vector<Vec3> path = {{0, 0, 0}, {0, 0, 2}, {1, 0, 2}, {1, 0, 0}};
  for (size_t i = 0; i < path.size(); ++i) {
    u.x0.push_back(path[i]);
    u.g1.push_back({1, 0, 0});
    u.g2.push_back({0, 1, 0});
    u.radius.push_back(0.1);
    u.fibres[0].push_back(Index(i));
  }
  const std::vector<SectionOutline> legs = cutSections(u, CutPlane{2, 1.0}, 12);
  REQUIRE(legs.size() == 2);
  CHECK(legs[0].centre.isApprox(Vec3(0, 0, 1)));
  CHECK(legs[1].centre.isApprox(Vec3(1, 0, 1)));
  // The median plane: normal to the longest span (z here), through its middle.
  const CutPlane m = medianPlane(u);
  CHECK(m.axis == 2);
  CHECK(m.value == doctest::Approx(1.0));
  CHECK(medianPlane(u, 0).value == doctest::Approx(0.5));
}

TEST_CASE("section: a fibre beside the plane is cut in a band, a shallow crossing in a long ellipse") {
  // Along x, length 2 (straightFibre's span), at height d below the plane z = 0: every section
  // disc meets it in a chord of half-length sqrt(R^2 - d^2), the band 2 sqrt(R^2 - d^2) wide.
  const double R = 0.1, d = 0.06, half = std::sqrt(R * R - d * d);
  const FibreFrame beside = straightFibre({0, 0, -d}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, R);
  const std::vector<SectionOutline> band = cutSections(beside, CutPlane{2, 0.0});
  REQUIRE(band.size() == 1);
  double lo = 1e9, hi = -1e9;
  for (const Vec3& p : band[0].points) {
    CHECK(p.z() == 0.0);
    CHECK(std::abs(p.y()) == doctest::Approx(half).epsilon(1e-12));
    lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
  }
  const double length = hi - lo;
  CHECK(std::abs(shoelace(band[0].points, 0, 1)) == doctest::Approx(2 * half * length).epsilon(1e-12));
  CHECK(cutSections(beside, CutPlane{2, -d - 1.01 * R}).empty());  // beyond its reach
  // Through the plane at 10 deg: t = (cos a, 0, sin a), g1 = (-sin a, 0, cos a), g2 = y; the
  // plane z = 0 cuts the ellipse of semi-axes R / sin a along x and R along y.
  const double a = 10 * std::numbers::pi / 180;
  const Vec3 t(std::cos(a), 0, std::sin(a)), g1(-std::sin(a), 0, std::cos(a)), g2(0, 1, 0);
  const std::vector<SectionOutline> shallow =
      cutSections(straightFibre(Vec3::Zero(), t, g1, g2, R), CutPlane{2, 0.0});
  REQUIRE(shallow.size() == 1);
  const double ax = R / std::sin(a);
  for (const Vec3& p : shallow[0].points)
    CHECK(std::pow(p.x() / ax, 2) + std::pow(p.y() / R, 2) == doctest::Approx(1).epsilon(1e-9));
  // The chords sample the ellipse every 1/16 element along x: its area within 1%.
  CHECK(std::abs(shoelace(shallow[0].points, 0, 1)) ==
        doctest::Approx(std::numbers::pi * ax * R).epsilon(0.01).scale(0));
}

TEST_CASE("section: a tool's surface quads are cut in segments, the fibres read from a VTU") {
  // Two quads: one across z = 0 (x from 0 to 2, z from -1 to 1), one above it.
  VtuArrays a;
  a["Points/"] = {0, 0, -1, 2, 0, -1, 2, 0, 1, 0, 0, 1, 0, 0, 2, 1, 0, 2, 1, 0, 3, 0, 0, 3};
  a["Cells/connectivity"] = {0, 1, 2, 3, 4, 5, 6, 7};
  a["Cells/offsets"] = {4, 8};
  a["Cells/types"] = {9, 9};
  const std::vector<Segment> cut = cutPolygons(a, CutPlane{2, 0.0});
  REQUIRE(cut.size() == 1);
  CHECK(std::abs(std::min(cut[0].a.x(), cut[0].b.x())) < 1e-12);
  CHECK(std::max(cut[0].a.x(), cut[0].b.x()) == doctest::Approx(2));
  CHECK(std::abs(cut[0].a.z()) < 1e-12);
  CHECK(std::abs(cut[0].b.z()) < 1e-12);
  // A fibre as the VTU holds it: a poly-line (type 4) over nodes 0..2, then its surface.
  VtuArrays v;
  v["Points/"] = {0, 0, 0, 0, 0, 1, 0, 0, 2, 9, 9, 9};
  v["PointData/g1"] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0};
  v["PointData/g2"] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0};
  v["PointData/radius"] = {0.1, 0.1, 0.1, 0.1};
  v["Cells/connectivity"] = {0, 1, 2, 3};
  v["Cells/offsets"] = {3, 4};
  v["Cells/types"] = {4, 1};
  const FibreFrame f = fibreFrameFromVtu(v);
  REQUIRE(f.fibres.size() == 1);
  CHECK(f.fibres[0] == std::vector<Index>{0, 1, 2});
  CHECK(f.x0.size() == 3);
  CHECK(cutSections(f, CutPlane{2, 1.5}, 8).size() == 1);
  v.erase("PointData/g2");
  CHECK(contains(messageOf([&] { fibreFrameFromVtu(v); }), "no array PointData/g2"));
}

TEST_CASE("history: a tool's displacement columns follow its motion, in mm on the axis") {
  TempDir dir("plot_tool_motion");
  const std::string scene = tinyScene(dir, Json::object());
  Json s = Json::parse(readFile(scene));
  s["tools"] = Json::array({{{"name", "far"}, {"type", "plane"}, {"point", {0, 5, 0}},
                             {"normal", {0, -1, 0}}, {"displacement", {0, 2, 0.5}},
                             {"table", "ramp"}}});
  writeFile(scene, s.dump());
  const RunResult r = runFibra({"run", scene, "--out", dir / "run", "--quiet"}, dir);
  REQUIRE_MESSAGE(r.status == 0, r.output);
  const auto rows = readCsv(dir / "run/history.csv");
  const auto& header = rows.at(0);
  const auto at = [&](const std::string& name) {
    const size_t c = size_t(std::find(header.begin(), header.end(), name) - header.begin());
    REQUIRE_MESSAGE(c < header.size(), name);
    return c;
  };
  const size_t t = at("time"), ux = at("tool.far.ux"), uy = at("tool.far.uy"),
               uz = at("tool.far.uz");
  REQUIRE(rows.size() == 4);
  for (size_t i = 1; i < rows.size(); ++i) {
    const double time = std::stod(rows[i][t]);  // the ramp table: the factor is the time
    CHECK(std::stod(rows[i][ux]) == 0.0);
    CHECK(std::stod(rows[i][uy]) == doctest::Approx(2 * time));
    CHECK(std::stod(rows[i][uz]) == doctest::Approx(0.5 * time));
  }
  CHECK(axisLabel("tool.far.uy") == "tool.far.uy (mm)");
}

TEST_CASE("output.plots: bad entries are refused at load time, unknown columns before solving") {
  TempDir dir("plot_scene_errors");
  const auto check = [&](const Json& plots) {
    const std::string scene = tinyScene(dir, Json{{"plots", plots}});
    return runFibra({"check", scene}, dir);
  };
  const std::vector<std::pair<Json, std::string>> cases = {
      {Json::array({{{"x", "time"}, {"y", "probe.tip.y"}, {"file", "tip.svg"}}}),
       "output.plots[0].file: must be a file name ending in .png (no folder), got 'tip.svg'"},
      {Json::array({{{"x", "time"}, {"y", "probe.tip.y"}, {"file", "../tip.png"}}}),
       "output.plots[0].file: must be a file name ending in .png"},
      {Json::array({{{"x", "time"}, {"y", Json::array()}, {"file", "tip.png"}}}),
       "output.plots[0].y: must name at least one history column"},
      {Json::array({{{"x", "time"}, {"y", 3}, {"file", "tip.png"}}}),
       "output.plots[0].y"},
      {Json::array({{{"x", "time"}, {"y", "probe.tip.y"}, {"file", "a.png"}},
                    {{"x", "time"}, {"y", "probe.tip.x"}, {"file", "a.png"}}}),
       "output.plots[1].file: 'a.png' repeated"},
      {Json::array({{{"x", "time"}, {"y", "probe.tip.y"}, {"file", "a.png"}, {"colour", 1}}}),
       "output.plots[0].colour: unknown field"},
      {Json::array({{{"x", "time"}, {"y", {"probe.tip.y", "probe.tip.w"}}, {"file", "a.png"}}}),
       "output.plots[0].y[1]: unknown column 'probe.tip.w' (did you mean 'probe.tip."},
      {Json::array({{{"x", "tme"}, {"y", "probe.tip.y"}, {"file", "a.png"}}}),
       "output.plots[0].x: unknown column 'tme' (did you mean 'time'?); the columns are: time,"},
  };
  for (const auto& [plots, message] : cases) {
    const RunResult r = check(plots);
    CHECK_MESSAGE(r.status == 2, r.output);
    CHECK_MESSAGE(contains(r.output, dir / "scene.json"), r.output);
    CHECK_MESSAGE(contains(r.output, message), r.output);
  }
  // A run refused for an unknown column creates nothing.
  const std::string scene = tinyScene(
      dir, Json{{"plots", Json::array({{{"x", "time"}, {"y", "nope"}, {"file", "a.png"}}})}});
  const RunResult r = runFibra({"run", scene, "--out", dir / "out"}, dir);
  CHECK(r.status == 2);
  CHECK(!fs::exists(dir / "out"));
}

TEST_CASE("plot and section: gnuplot missing or bad usage are clear errors") {
  TempDir dir("plot_cli_errors");
  const std::string scene = tinyScene(dir, Json::object());
  REQUIRE(runFibra({"run", scene, "--out", dir / "run", "--quiet"}, dir).status == 0);
  // Usage: exit 2 with the usage line.
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"plot", dir / "run", "--x", "time"}, "plot: missing --y"},
           {{"plot", dir / "run", "--x", "time", "--y", "a,,b"}, "--y: an empty column name"},
           {{"plot", "--x", "time", "--y", "iterations"}, "plot: missing the run directory"},
           {{"section", dir / "run", "--plane", "w=1"}, "--plane: expected x, y or z"},
           {{"section", dir / "run", "--plane", "z=abc"}, "--plane: expected x, y or z"},
           {{"section", dir / "run", "--frame", "-2"}, "--frame: expected frame numbers"},
           {{"section", dir / "run", "--frame", ""}, "--frame: expected frame numbers"},
           {{"section", dir / "run", "--colour", "red"}, "section: unknown option '--colour'"}}) {
    const RunResult r = runFibra(args, dir);
    CHECK_MESSAGE(r.status == 2, r.output);
    CHECK_MESSAGE(contains(r.output, message), r.output);
    CHECK_MESSAGE(contains(r.output, "\nusage: fibra " + args[0] + " RUN_DIR"), r.output);
  }
  // Bad input: exit 2 naming the file.
  RunResult r = runFibra({"plot", dir / "run", "--x", "time", "--y", "probe.tip.q"}, dir);
  CHECK(r.status == 2);
  CHECK(contains(r.output, (dir.path() / "run" / "history.csv").string() +
                               ": y: unknown column 'probe.tip.q'"));
  r = runFibra({"section", dir / "run", "--frame", "0,99", "--out", dir / "early.png"}, dir);
  CHECK(r.status == 2);
  CHECK(contains(r.output, "result.pvd: --frame: 99 outside 0..3 (or last)"));
  CHECK(!fs::exists(dir.path() / "early_0000.png"));  // every frame checked before the first
                                                      // is drawn
  r = runFibra({"section", dir / "run", "--plane", "x=50"}, dir);
  CHECK(r.status == 2);
  CHECK(contains(r.output, "the plane x = 50 mm cuts no fibre (the nodes span x = 0 to"));
  r = runFibra({"plot", dir / "nowhere", "--x", "time", "--y", "iterations"}, dir);
  CHECK(r.status == 2);
  CHECK(contains(r.output, "nowhere/history.csv: cannot read the history"));
  // No gnuplot: exit 1, the message says what to install; the script is there to run later.
  ::setenv("FIBRA_GNUPLOT", (dir / "no-gnuplot-here").c_str(), 1);
  r = runFibra({"plot", dir / "run", "--x", "time", "--y", "probe.tip.y", "--out",
                dir / "tip.png"},
               dir);
  const RunResult s = runFibra({"section", dir / "run", "--plane", "x=5"}, dir);
  ::unsetenv("FIBRA_GNUPLOT");
  CHECK(r.status == 1);
  CHECK_MESSAGE(contains(r.output, "gnuplot not found"), r.output);
  CHECK(contains(r.output, "apt-get install gnuplot-nox"));
  CHECK(fs::exists(dir / "tip.gp"));
  CHECK(!fs::exists(dir / "tip.png"));
  CHECK(s.status == 1);
  CHECK(contains(s.output, "gnuplot not found"));
  // A gnuplot that fails: exit 1 with its messages.
  writeFile(dir / "failing-gnuplot", "#!/bin/sh\necho \"line 3: undefined variable: x\" >&2\nexit 1\n");
  fs::permissions(dir / "failing-gnuplot", fs::perms::owner_all);
  ::setenv("FIBRA_GNUPLOT", (dir / "failing-gnuplot").c_str(), 1);
  r = runFibra({"plot", dir / "run", "--x", "time", "--y", "iterations"}, dir);
  ::unsetenv("FIBRA_GNUPLOT");
  CHECK(r.status == 1);
  CHECK_MESSAGE(contains(r.output, "failing-gnuplot failed on " +
                                       (dir.path() / "run" / "iterations_vs_time.gp").string() +
                                       " (exit 1): line 3: undefined variable: x"),
                r.output);
  CHECK(fs::exists(dir.path() / "run" / "section.dat"));
}

TEST_CASE("plot and section: gnuplot draws PNGs of a tiny run (skipped without gnuplot)") {
  if (findGnuplot().empty()) {
    MESSAGE("gnuplot is not installed: the PNGs are not checked (scripts/setup.sh installs it)");
    return;
  }
  TempDir dir("plot_png");
  const Json plots = Json::array(
      {{{"x", "probe.tip.y"}, {"y", "reaction.beam.start.fy"}, {"file", "force.png"}},
       {{"x", "time"}, {"y", {"iterations", "total_iterations"}}, {"file", "it's.png"},
        {"title", "Newton's iterations"}}});
  const std::string scene = tinyScene(dir, Json{{"plots", plots}});
  RunResult r = runFibra({"run", scene, "--out", dir / "run"}, dir);
  REQUIRE_MESSAGE(r.status == 0, r.output);
  CHECK(isPng((dir.path() / "run" / "force.png").string()));
  CHECK(isPng((dir.path() / "run" / "it's.png").string()));
  CHECK(fs::exists(dir.path() / "run" / "force.gp"));
  CHECK(contains(r.output, "fibra: plot "));
  r = runFibra({"plot", dir / "run", "--x", "time", "--y", "probe.tip.x,probe.tip.y", "--title",
                "tip; `rm -rf /` $(x)"},
               dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(isPng((dir.path() / "run" / "probe.tip.x_vs_time.png").string()));
  // RUN_DIR given relative to the working directory: the default picture still lies in RUN_DIR
  // (it went to RUN_DIR/RUN_DIR before), and so does the section's.
  const std::string relative = fs::relative(dir.path() / "run", fs::current_path()).string();
  r = runFibra({"plot", relative, "--x", "time", "--y", "total_iterations"}, dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(isPng((dir.path() / "run" / "total_iterations_vs_time.png").string()));
  r = runFibra({"section", relative, "--plane", "x=5", "--frame", "1"}, dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(isPng((dir.path() / "run" / "section.png").string()));
  // A picture named like an option, in a folder of its own, is still a file for gnuplot.
  r = runFibra({"plot", dir / "run", "--x", "time", "--y", "iterations", "--out",
                dir / "pictures/-v.png"},
               dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(isPng(dir / "pictures/-v.png"));
  CHECK(contains(readFile(dir / "pictures/-v.gp"), "plot '../run/history.csv' skip 1"));
  r = runFibra({"section", dir / "run", "--plane", "x=5", "--frame", "1", "--out",
                dir / "cut.png"},
               dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(contains(r.output, "1 sections by x = 5 mm at frame 1"));
  CHECK(isPng(dir / "cut.png"));
  CHECK(contains(readFile(dir / "cut.gp"), "set size ratio -1"));
  // Stages: one picture per frame, named by the frame's index.
  r = runFibra({"section", dir / "run", "--frame", "0,last", "--out", dir / "stage.png"}, dir);
  CHECK_MESSAGE(r.status == 0, r.output);
  CHECK(isPng(dir / "stage_0000.png"));
  CHECK(isPng(dir / "stage_0003.png"));
  CHECK(!fs::exists(dir / "stage.png"));
}
