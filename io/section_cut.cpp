#include "io/section_cut.h"

#include "io/plot.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace fibra {
namespace {

namespace fs = std::filesystem;

// A point of fibre `nodes` at s (node index + fraction), linear between nodes.
template <class F>
auto along(const std::vector<Index>& nodes, double s, F at) {
  const size_t i = std::min(size_t(s), nodes.size() - 2);
  const double t = s - double(i);
  return ((1 - t) * at(nodes[i]) + t * at(nodes[i + 1])).eval();
}

// The rim point of angle phi at node n: x0 + R (cos phi g1 + sin phi g2), mm.
Vec3 rimPoint(const FibreFrame& f, Index n, double phi) {
  return f.x0[n] + f.radius[n] * (std::cos(phi) * f.g1[n] + std::sin(phi) * f.g2[n]);
}

// The s where the rim line of angle phi meets the plane, nearest to `sc`; NaN when it does not.
double rimCrossing(const FibreFrame& f, const std::vector<Index>& nodes, const CutPlane& plane,
                   double phi, double sc) {
  const auto h = [&](Index n) { return rimPoint(f, n, phi)[plane.axis] - plane.value; };
  double best = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i + 1 < nodes.size(); ++i) {
    const double a = h(nodes[i]), b = h(nodes[i + 1]);
    if ((a < 0) == (b < 0)) continue;
    const double s = double(i) + a / (a - b);
    if (!(std::abs(s - sc) >= std::abs(best - sc))) best = s;
  }
  return best;
}

SectionOutline cutAt(const FibreFrame& f, Index fibre, const CutPlane& plane, double sc,
                     int sides) {
  const std::vector<Index>& nodes = f.fibres[fibre];
  SectionOutline out{fibre, sc, along(nodes, sc, [&](Index n) { return f.x0[n]; }), {}};
  for (int k = 0; k < sides; ++k) {
    const double phi = 2 * std::numbers::pi * k / sides;
    const double s = rimCrossing(f, nodes, plane, phi, sc);
    if (std::isnan(s)) continue;
    Vec3 p = along(nodes, s, [&](Index n) { return rimPoint(f, n, phi); });
    p[plane.axis] = plane.value;  // on the plane up to round-off: exactly on it
    out.points.push_back(p);
  }
  return out;
}

// A centreline crossing at least this steep (angle to the plane, rad) is cut along the rim lines;
// shallower, and where the fibre runs beside the plane, the cut is a band of chords.
constexpr double kSteepAngle = std::numbers::pi / 6;
constexpr int kChordsPerElement = 16;  // chord samples per element (band cuts)

// The chord of the section disc at s by the plane: the disc is c + a cos phi + b sin phi (a, b:
// R g1, R g2), its points on the plane have a_n cos phi + b_n sin phi = -(c_n - value) (n: the
// plane's axis), phi = psi +- acos(-h / rho) with rho = |(a_n, b_n)|, psi = atan2(b_n, a_n).
// False where the disc does not reach the plane.
bool chordAt(const FibreFrame& f, const std::vector<Index>& nodes, const CutPlane& plane,
             double s, Vec3& plus, Vec3& minus) {
  const Vec3 c = along(nodes, s, [&](Index n) { return f.x0[n]; });
  const Vec3 a = along(nodes, s, [&](Index n) { return (f.radius[n] * f.g1[n]).eval(); });
  const Vec3 b = along(nodes, s, [&](Index n) { return (f.radius[n] * f.g2[n]).eval(); });
  const double h = c[plane.axis] - plane.value, rho = std::hypot(a[plane.axis], b[plane.axis]);
  if (!(rho > 0) || std::abs(h) > rho) return false;
  const double psi = std::atan2(b[plane.axis], a[plane.axis]), delta = std::acos(-h / rho);
  plus = c + a * std::cos(psi + delta) + b * std::sin(psi + delta);
  minus = c + a * std::cos(psi - delta) + b * std::sin(psi - delta);
  plus[plane.axis] = minus[plane.axis] = plane.value;
  return true;
}

// Where the disc starts to reach the plane between sOut (no chord) and sIn (a chord), by
// bisection; the chord there is a point (the disc tangent to the plane).
Vec3 tangency(const FibreFrame& f, const std::vector<Index>& nodes, const CutPlane& plane,
              double sOut, double sIn) {
  Vec3 p, m;
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (sOut + sIn);
    (chordAt(f, nodes, plane, mid, p, m) ? sIn : sOut) = mid;
  }
  chordAt(f, nodes, plane, sIn, p, m);
  return 0.5 * (p + m);
}

// The centreline's crossings of the plane (node index + fraction) and whether each is steep.
std::vector<std::pair<double, bool>> crossings(const FibreFrame& f, const std::vector<Index>& nodes,
                                               const CutPlane& plane) {
  std::vector<std::pair<double, bool>> out;
  for (size_t i = 0; i + 1 < nodes.size(); ++i) {
    const double a = f.x0[nodes[i]][plane.axis] - plane.value,
                 b = f.x0[nodes[i + 1]][plane.axis] - plane.value;
    if ((a < 0) == (b < 0)) continue;
    const Vec3 t = f.x0[nodes[i + 1]] - f.x0[nodes[i]];
    out.emplace_back(double(i) + a / (a - b), std::abs(t[plane.axis]) >= std::sin(kSteepAngle) * t.norm());
  }
  return out;
}

// The band cuts of one fibre: each run of s where its discs reach the plane, without a steep
// crossing, is outlined by its chords' ends (one side forward, the other back), closed by the
// tangency points where the run starts and ends inside the fibre (a fibre end closes it with
// its end chord).
void bandSections(const FibreFrame& f, Index fibre, const CutPlane& plane,
                  const std::vector<std::pair<double, bool>>& cross,
                  std::vector<SectionOutline>& out) {
  const std::vector<Index>& nodes = f.fibres[fibre];
  const int samples = kChordsPerElement * int(nodes.size() - 1);
  const auto sOf = [&](int k) { return double(k) / kChordsPerElement; };
  Vec3 p, m;
  for (int k = 0; k <= samples; ++k) {  // k: a sample without a chord (or past the last)
    const int first = k;
    std::vector<Vec3> side1, side2;
    for (; k <= samples && chordAt(f, nodes, plane, sOf(k), p, m); ++k) {
      side1.push_back(p);
      side2.push_back(m);
    }
    if (side1.empty()) continue;
    const double s0 = sOf(first), s1 = sOf(k - 1);
    bool steep = false;
    for (const auto& [s, isSteep] : cross)
      steep |= isSteep && s >= s0 - 1.0 / kChordsPerElement && s <= s1 + 1.0 / kChordsPerElement;
    if (steep) continue;
    SectionOutline o{fibre, 0.5 * (s0 + s1), along(nodes, 0.5 * (s0 + s1), [&](Index n) { return f.x0[n]; }), {}};
    if (first > 0) o.points.push_back(tangency(f, nodes, plane, sOf(first - 1), s0));
    o.points.insert(o.points.end(), side1.begin(), side1.end());
    if (k <= samples) o.points.push_back(tangency(f, nodes, plane, sOf(k), s1));
    o.points.insert(o.points.end(), side2.rbegin(), side2.rend());
    o.centre[plane.axis] = plane.value;
    if (o.points.size() >= 3) out.push_back(std::move(o));
  }
}

const std::vector<double>& array(const VtuArrays& a, const std::string& key, size_t size) {
  const auto it = a.find(key);
  if (it == a.end()) throw std::runtime_error("VTU: no array " + key);
  if (it->second.size() < size) throw std::runtime_error("VTU: array " + key + " too short");
  return it->second;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::vector<SectionOutline> cutSections(const FibreFrame& f, const CutPlane& plane, int sides) {
  if (sides < 3) throw std::invalid_argument("cutSections: sides must be >= 3");
  std::vector<SectionOutline> out;
  for (Index fibre = 0; fibre < Index(f.fibres.size()); ++fibre) {
    const std::vector<std::pair<double, bool>> cross = crossings(f, f.fibres[fibre], plane);
    for (const auto& [s, steep] : cross) {
      if (!steep) continue;
      SectionOutline o = cutAt(f, fibre, plane, s, sides);
      if (o.points.size() >= 3) out.push_back(std::move(o));
    }
    bandSections(f, fibre, plane, cross, out);
  }
  return out;
}

CutPlane medianPlane(const FibreFrame& f, int axis) {
  if (f.x0.empty()) throw std::invalid_argument("medianPlane: no nodes");
  Vec3 lo = f.x0[0], hi = f.x0[0];
  for (const Vec3& x : f.x0) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (axis < 0) (hi - lo).maxCoeff(&axis);
  return {axis, 0.5 * (lo[axis] + hi[axis])};
}

std::array<int, 2> planeAxes(int axis) { return {(axis + 1) % 3, (axis + 2) % 3}; }

FibreFrame fibreFrameFromVtu(const VtuArrays& a) {
  const std::vector<double>& types = array(a, "Cells/types", 0);
  const std::vector<double>& offsets = array(a, "Cells/offsets", types.size());
  const std::vector<double>& connectivity =
      array(a, "Cells/connectivity", types.empty() ? 0 : size_t(offsets[types.size() - 1]));
  FibreFrame f;
  Index nodes = 0;
  for (size_t c = 0; c < types.size(); ++c) {
    if (types[c] != 4) continue;  // VTK_POLY_LINE: a fibre's centreline
    std::vector<Index>& fibre = f.fibres.emplace_back();
    for (size_t k = c ? size_t(offsets[c - 1]) : 0; k < size_t(offsets[c]); ++k)
      fibre.push_back(Index(connectivity[k]));
    if (fibre.size() < 2) throw std::runtime_error("VTU: a fibre with fewer than 2 nodes");
    for (Index n : fibre) {
      if (n < 0) throw std::runtime_error("VTU: a negative point index");
      nodes = std::max(nodes, n + 1);
    }
  }
  const std::vector<double>& points = array(a, "Points/", 3 * size_t(nodes));
  const std::vector<double>& g1 = array(a, "PointData/g1", 3 * size_t(nodes));
  const std::vector<double>& g2 = array(a, "PointData/g2", 3 * size_t(nodes));
  const std::vector<double>& radius = array(a, "PointData/radius", size_t(nodes));
  for (Index n = 0; n < nodes; ++n) {
    f.x0.emplace_back(points[3 * n], points[3 * n + 1], points[3 * n + 2]);
    f.g1.emplace_back(g1[3 * n], g1[3 * n + 1], g1[3 * n + 2]);
    f.g2.emplace_back(g2[3 * n], g2[3 * n + 1], g2[3 * n + 2]);
    f.radius.push_back(radius[n]);
  }
  return f;
}

std::vector<PvdFrame> readRunFrames(const std::string& runDir) {
  const fs::path pvd = fs::path(runDir) / "result.pvd";
  if (!std::ifstream(pvd))
    throw PlotInputError(pvd.string() + ": cannot read the frames (is " + runDir +
                         " a fibra run's output directory, with output.vtu on?)");
  try {
    return readPvdFrames(readText(pvd));
  } catch (const std::runtime_error& e) {
    throw PlotInputError(pvd.string() + ": " + e.what());
  }
}

int frameIndex(const std::string& runDir, int index, int count) {
  const int last = count - 1;
  if (index < -1 || index > last)
    throw PlotInputError((fs::path(runDir) / "result.pvd").string() + ": --frame: " +
                         std::to_string(index) + " outside 0.." + std::to_string(last) +
                         " (or last)");
  return index < 0 ? last : index;
}

FibreFrame readFibreFrame(const std::string& runDir, int index, int* chosen) {
  const std::vector<PvdFrame> frames = readRunFrames(runDir);
  const int k = frameIndex(runDir, index, int(frames.size()));
  const fs::path vtu = fs::path(runDir) / frames[size_t(k)].file;
  if (!std::ifstream(vtu))
    throw PlotInputError(vtu.string() + ": cannot read frame " + std::to_string(k));
  try {
    FibreFrame f = fibreFrameFromVtu(readVtuArrays(readText(vtu)));
    f.time = frames[size_t(k)].time;
    f.file = vtu.string();
    if (chosen) *chosen = k;
    return f;
  } catch (const std::runtime_error& e) {
    throw PlotInputError(vtu.string() + ": " + e.what());
  }
}

std::vector<Segment> cutPolygons(const VtuArrays& a, const CutPlane& plane) {
  const std::vector<double>& offsets = array(a, "Cells/offsets", 0);
  const std::vector<double>& connectivity =
      array(a, "Cells/connectivity", offsets.empty() ? 0 : size_t(offsets.back()));
  const std::vector<double>& points = array(a, "Points/", 0);
  const auto point = [&](double i) {
    if (i < 0 || 3 * size_t(i) + 2 >= points.size())
      throw std::runtime_error("VTU: a point index out of range");
    return Vec3(points[3 * size_t(i)], points[3 * size_t(i) + 1], points[3 * size_t(i) + 2]);
  };
  std::vector<Segment> out;
  for (size_t c = 0, from = 0; c < offsets.size(); from = size_t(offsets[c++])) {
    std::vector<Vec3> crossings;  // where the polygon's edges cross the plane
    for (size_t k = from; k < size_t(offsets[c]); ++k) {
      const Vec3 p = point(connectivity[k]);
      const Vec3 q = point(connectivity[k + 1 < size_t(offsets[c]) ? k + 1 : from]);
      const double hp = p[plane.axis] - plane.value, hq = q[plane.axis] - plane.value;
      if ((hp < 0) != (hq < 0)) crossings.push_back(p + hp / (hp - hq) * (q - p));
    }
    if (crossings.size() == 2) out.push_back({crossings[0], crossings[1]});
  }
  return out;
}

std::vector<Segment> readToolCut(const std::string& frameFile, const CutPlane& plane) {
  const std::string name = fs::path(frameFile).filename().string();  // result_0007.vtu
  const size_t cut = name.rfind('_');
  if (cut == std::string::npos) return {};
  const fs::path tools = fs::path(frameFile).parent_path() /
                         (name.substr(0, cut) + "_tools" + name.substr(cut));
  if (!fs::exists(tools)) return {};
  try {
    return cutPolygons(readVtuArrays(readText(tools)), plane);
  } catch (const std::runtime_error& e) {
    throw PlotInputError(tools.string() + ": " + e.what());
  }
}

}  // namespace fibra
