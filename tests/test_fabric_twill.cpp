// The reduced twill of samples/fabric_twill_biaxial.json (3 x 3 yarns of 3 fibres, a 2/1 twill:
// each warp yarn over two weft yarns, under one; scripts/fabric_loadings.py --weave twill writes
// it): the initial geometry (forced normals, the normal rules back under damping, an undamped
// settle) converges in every increment; after it no fibre overlaps a fibre of another yarn by
// more than p_max, and at every crossing the yarn the pattern puts over lies above the other, both measured from the
// nodes alone (tests/centreline_measure.h, not the contact elements);
// then biaxial tension converges in every increment with a rising edge force in both directions.
#include "centreline_measure.h"
#include "engine/world.h"
#include "io/fabric_generator.h"
#include "io/scene_loader.h"
#include "scene_test_util.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace fibra;
using namespace fibra::test;

namespace {

constexpr int kYarns = 3;         // in each direction
constexpr double kSpacing = 1.5;  // between yarn axes, mm
constexpr double kLength = 6;     // of every fibre, (kYarns + 1) x kSpacing, mm

Index fibreNamed(const World& w, const std::string& name) {
  const std::vector<std::string>& names = w.fibres().name;
  const auto it = std::find(names.begin(), names.end(), name);
  REQUIRE_MESSAGE(it != names.end(), "no fibre " << name);
  return Index(it - names.begin());
}

// Fibre k of warp (or weft) yarn y.
Index fibreOf(const World& w, const char* dir, int y, int k) {
  return fibreNamed(w, std::string("fab.") + dir + std::to_string(y) + ".f" + std::to_string(k));
}

// The axis coordinate of yarn y across its direction, and arc length s of a coordinate along a
// fibre, mm.
double axis(int y) { return (y - (kYarns - 1) / 2.0) * kSpacing; }
double arc(double coordinate) { return coordinate + kLength / 2; }

struct Crossings {
  double worstOverlap = -1e300;  // largest w_I + w_J - d over the fibre pairs of the crossings
                                 // (tests/centreline_measure.h overlapAt), mm
  int inOrder = 0, total = 0;    // crossings whose over yarn lies above the other
};

// Warp yarn c crosses weft yarn r at (x_r, y_c): over each pair of their fibres, the closest
// approach of the centrelines near there; the yarns' mean heights z at the crossing.
Crossings measureCrossings(const World& w, const WeavePattern& pattern) {
  const FibreStore& fs = w.fibres();
  Crossings m;
  for (int c = 0; c < kYarns; ++c)
    for (int r = 0; r < kYarns; ++r) {
      const double sWarp = arc(axis(r)), sWeft = arc(axis(c));
      double zWarp = 0, zWeft = 0;
      for (int k = 0; k < 3; ++k) {
        const Index I = fibreOf(w, "warp", c, k), J = fibreOf(w, "weft", r, k);
        zWarp += centreline(fs, fs.q, I, sWarp).z() / 3;
        zWeft += centreline(fs, fs.q, J, sWeft).z() / 3;
        for (int l = 0; l < 3; ++l) {
          const Index L = fibreOf(w, "weft", r, l);
          const Closest d = closestApproach(fs, fs.q, I, L, sWarp, sWeft);
          m.worstOverlap = std::max(m.worstOverlap, overlapAt(fs, fs.q, I, L, d));
        }
      }
      const bool warpOver = pattern[r % pattern.size()][c % pattern[0].size()] == 1;
      m.inOrder += warpOver ? zWarp > zWeft : zWeft > zWarp;
      ++m.total;
    }
  return m;
}

}  // namespace

TEST_CASE("fabric loadings: a reduced 3 x 3 twill weaves in the pattern's order and takes biaxial tension") {
  World w(loadScene(sourcePath("samples/fabric_twill_biaxial.json")));
  const SceneDef& s = w.scene();
  REQUIRE(s.steps.size() == 4);
  // The initial geometry: forced normals, the normal rules (damped), the settle.
  while (w.currentStep() < 3) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
  }
  const Crossings m = measureCrossings(w, twillWeave(2, 1));
  MESSAGE("after the initial geometry: largest overlap between yarns " << m.worstOverlap
          << " mm (p_max " << s.contact.maxPenetration << "), " << m.inOrder << " of "
          << m.total << " crossings in the pattern's order");
  // The aim, against the independent measure: no two fibres of different yarns overlap
  // by more than p_max (0.87 p_max measured; 1.16 p_max before frictionless crossings followed
  // their closest points in loop B, systems/crossing_follow.h; docs/RESULTS.md "Woven fabric,
  // reduced: test loadings", the twill).
  CHECK(m.worstOverlap <= s.contact.maxPenetration);
  CHECK(m.inOrder == m.total);
  CHECK(m.total == kYarns * kYarns);

  // Biaxial tension: every fibre start pulled back along its yarn, the ends held.
  const Index warpEnd = 0, weftEnd = 1;  // the first two conditions hold fab.warp.end, fab.weft.end
  REQUIRE(s.bcs[warpEnd].group == "fab.warp.end");
  REQUIRE(s.bcs[weftEnd].group == "fab.weft.end");
  std::vector<double> warp{w.reaction(warpEnd).force.x()}, weft{w.reaction(weftEnd).force.y()};
  while (!w.finished()) {
    const StepReport r = w.step();
    REQUIRE_MESSAGE(r.status == StepStatus::Converged, r.message);
    warp.push_back(w.reaction(warpEnd).force.x());
    weft.push_back(w.reaction(weftEnd).force.y());
  }
  REQUIRE(warp.size() == 21);
  for (size_t i = 1; i < warp.size(); ++i) {
    CAPTURE(i);
    CHECK(warp[i] > warp[i - 1]);
    CHECK(weft[i] > weft[i - 1]);
  }
  MESSAGE("biaxial edge force from " << warp[0] << " / " << weft[0] << " N to " << warp.back()
                                     << " / " << weft.back() << " N (warp / weft)");
  CHECK(warp.back() > 1);  // N
  CHECK(weft.back() > 1);
}
