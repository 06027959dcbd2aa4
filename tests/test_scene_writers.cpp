// Output writers: the VTU geometry (centrelines and the surface built from the directors), the
// PVD series, the final-state file read back exactly, the history's columns and reactions, and
// files that are never left half-written.
#include "engine/fibre_builder.h"
#include "io/scene_loader.h"
#include "engine/world.h"
#include "contact_scenes.h"
#include "scene_test_util.h"
#include "io/history_writer.h"
#include "io/output_file.h"
#include "io/state_writer.h"
#include "io/vtu_writer.h"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <regex>

using namespace fibra;
using namespace fibra::test;

namespace {

// A straight fibre along x and a helix, in one store.
FibreStore twoFibres() {
  FibreStore fs;
  FibreDef line;
  line.name = "line";
  line.radius = 0.1;
  line.elements = 3;
  line.geometry.points = {Vec3::Zero(), Vec3(3, 0, 0)};
  addFibre(fs, line, 0, "fibres[0]");
  FibreDef helix;
  helix.name = "helix";
  helix.radius = 0.05;
  helix.elements = 4;
  helix.order = 1;
  helix.geometry.kind = GeometryKind::Helix;
  helix.geometry.helixRadius = 0.5;
  helix.geometry.pitch = 1;
  helix.geometry.turns = 1;
  addFibre(fs, helix, 0, "fibres[1]");
  return fs;
}

// The numbers of the DataArray whose opening tag contains `tag` (ASCII format).
std::vector<double> dataArray(const std::string& xml, const std::string& tag) {
  const size_t at = xml.find(tag);
  REQUIRE(at != std::string::npos);
  const size_t begin = xml.find('>', at) + 1, end = xml.find("</DataArray>", begin);
  std::istringstream in(xml.substr(begin, end - begin));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

WorldDef oneThread() {
  WorldDef def;
  def.threads = 1;
  return def;
}

Vec3 point(const std::vector<double>& xyz, size_t i) {
  return Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

}  // namespace

TEST_CASE("VTU writer: centrelines at x0 and a closed surface at radius R from the directors") {
  TempDir dir("vtu");
  fs::create_directories(dir.path());
  FibreStore fibres = twoFibres();
  Eigen::VectorXd q = fibres.qRef;
  // Stretch the first node's g1: its section becomes an ellipse with semi-axis 2R along g1.
  g1Of(q, 0) *= 2;
  const int sides = 8;
  writeVtu(dir / "f.vtu", fibres, q, {sides, VtuEncoding::Ascii});
  const std::string xml = readFile(dir / "f.vtu");
  const Index nodes = fibres.nodes();  // 7 + 5
  CHECK(xml.find("NumberOfPoints=\"" + std::to_string(nodes * (1 + sides)) + "\"") !=
        std::string::npos);
  // Cells: per fibre one poly-line, (nodes - 1) * sides quads, two end caps.
  const int cells = 2 + (6 + 4) * sides + 4;
  CHECK(xml.find("NumberOfCells=\"" + std::to_string(cells) + "\"") != std::string::npos);

  const std::vector<double> pts =
      dataArray(xml, "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format");
  REQUIRE(pts.size() == size_t(3 * nodes * (1 + sides)));
  for (Index n = 0; n < nodes; ++n)
    CHECK(point(pts, n) == Vec3(x0Of(q, n)));  // exact: shortest round trip
  for (Index n = 0; n < nodes; ++n) {
    const double R = fibres.radius[fibres.nodeFibre[n]];
    const Vec3 t = g1Of(fibres.qRef, n).cross(g2Of(fibres.qRef, n));
    for (int k = 0; k < sides; ++k) {
      const Vec3 d = point(pts, nodes + n * sides + k) - x0Of(q, n);
      CHECK(std::abs(d.dot(t)) < 1e-12);  // in the section plane
      if (n > 0) CHECK(d.norm() == doctest::Approx(R).epsilon(1e-12).scale(0));
    }
  }
  // Node 0: phi = 0 lies along the stretched g1 at 2R, phi = pi/2 along g2 at R.
  CHECK((point(pts, nodes) - x0Of(q, 0)).norm() == doctest::Approx(0.2).epsilon(1e-12).scale(0));
  CHECK((point(pts, nodes + 2) - x0Of(q, 0)).norm() ==
        doctest::Approx(0.1).epsilon(1e-12).scale(0));

  const std::vector<double> types = dataArray(xml, "Name=\"types\"");
  CHECK(std::count(types.begin(), types.end(), 4.0) == 2);           // poly-lines
  CHECK(std::count(types.begin(), types.end(), 9.0) == 10 * sides);  // quads
  CHECK(std::count(types.begin(), types.end(), 7.0) == 4);           // end caps
  const std::vector<double> offsets = dataArray(xml, "Name=\"offsets\"");
  const std::vector<double> connectivity = dataArray(xml, "Name=\"connectivity\"");
  CHECK(offsets.back() == double(connectivity.size()));
  CHECK(*std::max_element(connectivity.begin(), connectivity.end()) == nodes * (1 + sides) - 1);
  CHECK(dataArray(xml, "Name=\"radius\"").size() == size_t(nodes * (1 + sides)));
  CHECK_FALSE(fs::exists(dir / "f.vtu.part"));
}

TEST_CASE("VTU series: the PVD lists exactly the frames written, with their times") {
  TempDir dir("pvd");
  fs::create_directories(dir.path());
  const FibreStore fibres = twoFibres();
  VtuSeries series(dir.path().string());
  for (double t : {0.0, 0.25, 1.5}) series.write(fibres, fibres.qRef, t);
  CHECK(series.frames() == 3);
  const std::string pvd = readFile(dir / "result.pvd");
  const std::regex dataset("<DataSet timestep=\"([^\"]+)\" part=\"0\" file=\"([^\"]+)\"/>");
  std::vector<std::pair<std::string, std::string>> listed;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it)
    listed.emplace_back((*it)[1], (*it)[2]);
  REQUIRE(listed.size() == 3);
  CHECK(listed[0] == std::pair<std::string, std::string>{"0", "result_0000.vtu"});
  CHECK(listed[1] == std::pair<std::string, std::string>{"0.25", "result_0001.vtu"});
  CHECK(listed[2] == std::pair<std::string, std::string>{"1.5", "result_0002.vtu"});
  for (const auto& [time, file] : listed) CHECK(fs::exists(dir / file));
  for (const auto& entry : fs::directory_iterator(dir.path()))
    CHECK(entry.path().extension() != ".part");
}

TEST_CASE("contact VTU: one line per contact element, forces that balance the load") {
  // Two crossing beams pressed together by P at B's midspan: the contact file holds the
  // elements from x^I to x^J with their normal forces, which sum to the P/2 the contact carries.
  const double P = 0.02;
  World world(crossingBeams(P, 1e-4), oneThread());
  while (!world.finished()) REQUIRE(world.step().status == StepStatus::Converged);
  const ContactSnapshot c = world.contactSnapshot();
  REQUIRE(c.size() >= 1);
  TempDir dir("contact_vtu");
  fs::create_directories(dir.path());
  VtuSeries series(dir.path().string(), "result", {.encoding = VtuEncoding::Ascii});
  series.write(world.fibres(), world.fibres().q, world.time(), &c);
  series.write(world.fibres(), world.fibres().q, 2 * world.time());  // a frame without contacts
  const std::string xml = readFile(dir / "result_contacts_0000.vtu");
  const std::vector<double> points = dataArray(xml.substr(xml.find("<Points>")), "<DataArray");
  const std::vector<double> normal = dataArray(xml, "Name=\"normal\""),
                            force = dataArray(xml, "Name=\"normal_force\""),
                            gap = dataArray(xml, "Name=\"gap\"");
  REQUIRE(points.size() == 6 * size_t(c.size()));
  REQUIRE(force.size() == size_t(c.size()));
  const std::vector<double> zone = dataArray(xml, "Name=\"zone\""),
                            refined = dataArray(xml, "Name=\"refined\"");
  REQUIRE(zone.size() == size_t(c.size()));
  REQUIRE(refined.size() == size_t(c.size()));
  for (Index e = 0; e < c.size(); ++e) {
    CHECK(zone[e] == double(c.zone[e]));
    CHECK(refined[e] == double(c.refined[e]));
  }
  double total = 0;
  for (Index e = 0; e < c.size(); ++e) {
    const Vec3 xI = point(points, 2 * e), xJ = point(points, 2 * e + 1), N = point(normal, e);
    CHECK((xI - c.particleI[e]).norm() == 0);
    CHECK(N.norm() == doctest::Approx(1));
    CHECK((xI - xJ).dot(N) == doctest::Approx(gap[e]).epsilon(1e-9).scale(0));
    total += force[e] * std::abs(N.z());
  }
  CHECK(total == doctest::Approx(P / 2).epsilon(0.02).scale(0));
  const std::string pvd = readFile(dir / "result.pvd");
  CHECK(pvd.find("part=\"1\" file=\"result_contacts_0000.vtu\"") != std::string::npos);
  CHECK(pvd.find("result_contacts_0001.vtu") == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "result_contacts_0001.vtu"));
}

TEST_CASE("state writer: every node's nine values read back exactly") {
  TempDir dir("state");
  fs::create_directories(dir.path());
  const FibreStore fibres = twoFibres();
  Eigen::VectorXd q = fibres.qRef;
  q += Eigen::VectorXd::LinSpaced(q.size(), 0, 1) / 3;  // values without short decimals
  writeState(dir / "state.csv", fibres, q);
  const auto rows = readCsv(dir / "state.csv");
  REQUIRE(rows.size() == size_t(fibres.nodes() + 1));
  CHECK(rows[0] == std::vector<std::string>{"fibre", "node", "x", "y", "z", "g1x", "g1y", "g1z",
                                            "g2x", "g2y", "g2z"});
  for (Index n = 0; n < fibres.nodes(); ++n) {
    const auto& row = rows[n + 1];
    REQUIRE(row.size() == 11);
    const Index f = fibres.nodeFibre[n];
    CHECK(row[0] == fibres.name[f]);
    CHECK(std::stoi(row[1]) == n - fibres.firstNode[f]);
    for (int k = 0; k < kNodeDofs; ++k)
      CHECK(std::strtod(row[2 + k].c_str(), nullptr) == q(kNodeDofs * n + k));
  }
}

TEST_CASE("output file: appears only when committed, never as a partial file") {
  TempDir dir("atomic");
  fs::create_directories(dir.path());
  {
    OutputFile file(dir / "a.txt");
    file.stream() << "half";
    CHECK(fs::exists(dir / "a.txt.part"));
    CHECK_FALSE(fs::exists(dir / "a.txt"));
  }  // abandoned
  CHECK_FALSE(fs::exists(dir / "a.txt"));
  CHECK_FALSE(fs::exists(dir / "a.txt.part"));
  writeFile(dir / "b.txt", "old");
  {
    OutputFile file(dir / "b.txt");
    file.stream() << "new";
    CHECK(readFile(dir / "b.txt") == "old");  // the previous complete file until commit
    file.commit();
  }
  CHECK(readFile(dir / "b.txt") == "new");
  CHECK_THROWS_AS(OutputFile(dir / "no_such_dir/c.txt"), std::runtime_error);
}

TEST_CASE("history writer: columns of every family, reactions in equilibrium with the load") {
  TempDir dir("history");
  fs::create_directories(dir.path());
  SceneDef scene = loadScene(sourcePath("samples/cantilever.json"));
  scene.steps[0].increments = 3;
  scene.output.momentPoint = Vec3(0, 0, 0);
  World world(scene, oneThread());
  const std::string path = dir / "history.csv";
  std::vector<double> extraValues;
  {
    std::vector<HistoryColumns> columns = standardHistoryColumns(world);
    columns.push_back({{"extra.increment_squared"},
                       [&](const World&, const StepReport& r, std::vector<double>& row) {
                         row.push_back(r.increment * r.increment);
                       }});
    HistoryWriter history(path, std::move(columns));
    while (!world.finished()) {
      const StepReport r = world.step();
      REQUIRE(r.status == StepStatus::Converged);
      history.append(world, r);
      CHECK(fs::exists(path + ".part"));
      CHECK_FALSE(fs::exists(path));
    }
    history.close();
  }
  CHECK_FALSE(fs::exists(path + ".part"));
  const auto rows = readCsv(path);
  const std::vector<std::string> header = {"time",
                                           "step",
                                           "increment",
                                           "load_factor",
                                           "iterations",
                                           "total_iterations",
                                           "cutbacks",
                                           "sub_increments",
                                           "smallest_increment",
                                           "predicted",
                                           "predictor_retries",
                                           "normal_retries",
                                           "damped_steps",
                                           "residual",
                                           "wall_s",
                                           "reaction.beam.start.fx",
                                           "reaction.beam.start.fy",
                                           "reaction.beam.start.fz",
                                           "reaction.beam.start.mx",
                                           "reaction.beam.start.my",
                                           "reaction.beam.start.mz",
                                           "energy.strain",
                                           "energy.external",
                                           "energy.supports",
                                           "energy.contact_normal",
                                           "energy.friction",
                                           "energy.tools",
                                           "energy.stabilisation",
                                           "energy.error",
                                           "linear.factorisations",
                                           "linear.solves",
                                           "linear.fallbacks",
                                           "linear.krylov_iterations",
                                           "linear.krylov_max",
                                           "linear.krylov_failures",
                                           "probe.tip.x",
                                           "probe.tip.y",
                                           "probe.tip.z",
                                           "extra.increment_squared"};
  REQUIRE(rows.size() == 4);
  CHECK(rows[0] == header);
  auto value = [&](size_t row, const std::string& column) {
    return std::stod(rows[row][std::find(header.begin(), header.end(), column) - header.begin()]);
  };
  const double P = -scene.loads[0].vector.y();
  for (size_t i = 1; i <= 3; ++i) {
    CAPTURE(i);
    REQUIRE(rows[i].size() == header.size());
    CHECK(value(i, "time") == doctest::Approx(i / 3.0).epsilon(1e-14));
    CHECK(value(i, "step") == 1);
    CHECK(value(i, "increment") == i);
    CHECK(value(i, "iterations") >= 1);
    CHECK(value(i, "residual") <= scene.steps[0].forceTolerance);
    // The reaction (what the clamp exerts on the beam) balances the tip load F = (0, -P t, 0) and
    // its moment about the origin, tip x F, the lever arm read from the probe columns.
    const double Fy = -P * value(i, "time");
    CHECK(value(i, "reaction.beam.start.fy") == doctest::Approx(-Fy).epsilon(1e-6).scale(0));
    CHECK(std::abs(value(i, "reaction.beam.start.fx")) < 1e-9 * P);
    CHECK(value(i, "reaction.beam.start.mz") ==
          doctest::Approx(-value(i, "probe.tip.x") * Fy).epsilon(1e-6).scale(0));
    CHECK(value(i, "extra.increment_squared") == i * i);
    // The direct strategy factorises afresh at every Newton iteration and runs no GMRES.
    CHECK(value(i, "linear.factorisations") == value(i, "total_iterations"));
    CHECK(value(i, "linear.solves") >= value(i, "linear.factorisations"));
    CHECK(value(i, "linear.krylov_iterations") == 0);
  }
  // The last row's probe is the world's final tip position, to the last bit.
  const Vec3 tip = x0Of(world.fibres().q, world.fibres().nodes() - 1);
  CHECK(value(3, "probe.tip.y") == tip.y());
}

TEST_CASE("history writer: repeated column names and miscounted families are refused") {
  TempDir dir("history_bad");
  fs::create_directories(dir.path());
  SceneDef scene = loadScene(sourcePath("samples/cantilever.json"));
  World world(scene, oneThread());
  const auto noValues = [](const World&, const StepReport&, std::vector<double>&) {};
  CHECK_THROWS_AS(HistoryWriter(dir / "h.csv", {incrementColumns(), {{"time"}, noValues}}),
                  std::invalid_argument);
  HistoryWriter history(
      dir / "h2.csv", {{{"a", "b"}, [](const World&, const StepReport&, std::vector<double>& row) {
                          row.push_back(1);
                        }}});
  CHECK_THROWS_AS(history.append(world, StepReport{}), std::logic_error);
  history.close();
  CHECK_THROWS_AS(history.append(world, StepReport{}), std::logic_error);
}
