// The neo-Hookean section law (materials' `law` "neo_hookean", systems/section_law.h): its
// derivatives against central differences, pointwise and through the beam element (with the
// enhanced transverse strains condensed); Saint Venant-Kirchhoff's tangent at zero strain (EA, EI,
// GJ against closed form: tests/test_beam_stiffness.cpp); a rod compressed far past Saint
// Venant-Kirchhoff's turning point against the closed-form uniaxial response of the compressible
// neo-Hookean solid; and a thick rod rolled up to R kappa = 0.63, where Saint Venant-Kirchhoff's
// bending moment has turned back.
#include "beam_fixtures.h"
#include "engine/fibre_builder.h"
#include "engine/scene.h"
#include "systems/beam_element.h"
#include "systems/beam_section.h"
#include "systems/section_law.h"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

using namespace fibra;

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
constexpr int kComp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

constexpr double kYoung = 4000, kNu = 0.3;
const double kLambda = kYoung * kNu / ((1 + kNu) * (1 - 2 * kNu));
const double kMu = kYoung / (2 * (1 + kNu));

struct Rod {
  FibreStore fs;
  MaterialStore mats;
  BeamStore beams;
};

// One fibre of `elements` elements on the material's law: the straight line `points` or a helix.
Rod makeRod(MaterialLaw law, GeometryKind kind, int order, double fBend = 1, int elements = 3,
            std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(1.5, 0.3, -0.2)}) {
  Rod o;
  o.mats.name = {"m"};
  o.mats.youngModulus = {kYoung};
  o.mats.poissonRatio = {kNu};
  o.mats.bendingFactor = {fBend};
  o.mats.torsionFactor = {0.7};
  o.mats.law = {law};
  FibreDef def;
  def.name = "f";
  def.radius = 0.1;
  def.elements = elements;
  def.order = order;
  def.geometry.points = std::move(points);
  if (kind == GeometryKind::Helix) {
    def.geometry.kind = GeometryKind::Helix;
    def.geometry.helixRadius = 0.4;
    def.geometry.pitch = 1.2;
    def.geometry.turns = 0.4;
    def.geometry.phase = 0.3;
  }
  addFibre(o.fs, def, 0, "fibres[0]");
  buildBeamReference(o.fs, o.mats, {BeamIntegration{}}, o.beams);
  return o;
}

template <int Order>
ElementVector<Order> elementDofs(const Eigen::VectorXd& q, const FibreStore& fs, Index e) {
  return q.segment<kElementDofs<Order>>(kNodeDofs * fs.elementFirstNode[e]);
}

// A symmetric positive definite metric, not the identity (a sheared, stretched section basis).
Mat3 someMetric() {
  Mat3 A;
  A << 1.1, 0.2, -0.1, 0.05, 0.9, 0.15, 0.1, -0.2, 1.3;
  return A.transpose() * A;
}

// Saint Venant-Kirchhoff's B_p : C : B_q on the metric with inverse gCon, written out
// independently of section_law.cpp: lambda (G^-1:B_p)(G^-1:B_q) + 2 mu tr(G^-1 B_p G^-1 B_q).
Mat6 svkTangent(const Mat3& gCon) {
  auto basis = [](int p) {
    Mat3 B = Mat3::Zero();
    B(kComp[p][0], kComp[p][1]) = B(kComp[p][1], kComp[p][0]) = 1;
    return B;
  };
  Mat6 c;
  for (int p = 0; p < 6; ++p)
    for (int q = 0; q < 6; ++q)
      c(p, q) = kLambda * gCon.cwiseProduct(basis(p)).sum() * gCon.cwiseProduct(basis(q)).sum() +
                2 * kMu * (gCon * basis(p) * gCon * basis(q)).trace();
  return c;
}

// The compressible neo-Hookean bar in uniaxial stress: transverse stretch t of the axial
// stretch a, from mu (t^2 - 1) + lambda ln(a t^2) = 0 (Newton), and the nominal axial stress
// P = mu (a - 1/a) + lambda ln(a t^2) / a (MPa).
struct Uniaxial {
  double t, P;
};
Uniaxial uniaxialNeoHookean(double a) {
  double t = 1;
  for (int k = 0; k < 50; ++k) {
    const double g = kMu * (t * t - 1) + kLambda * std::log(a * t * t);
    t -= g / (2 * kMu * t + 2 * kLambda / t);
  }
  return {t, kMu * (a - 1 / a) + kLambda * std::log(a * t * t) / a};
}

// A straight rod along x stretched homogeneously: x0 scaled by a along the axis, both directors
// by t. Returns the axial force at the end node, N (the element's force on the end's x), and the
// largest director force, N mm.
struct EndForce {
  double axial, directors;
};
EndForce homogeneousStretch(MaterialLaw law, double a, double t) {
  const Rod o = makeRod(law, GeometryKind::Line, 2, 1, 1, {Vec3(0, 0, 0), Vec3(1, 0, 0)});
  Eigen::VectorXd q = o.fs.qRef;
  for (Index n = 0; n < o.fs.nodes(); ++n) {
    x0Of(q, n).x() *= a;
    g1Of(q, n) *= t;
    g2Of(q, n) *= t;
  }
  ElementVector<2> f;
  beamElement<2>(elementPoints(o.beams, 0), elementDofs<2>(q, o.fs, 0), f, nullptr);
  double directors = 0;
  for (int n = 0; n < 3; ++n) directors = std::max(directors, f.segment<6>(kNodeDofs * n + 3).cwiseAbs().maxCoeff());
  return {f(kNodeDofs * 2), directors};
}

}  // namespace

TEST_CASE("neo-Hookean point law: stress and tangent against central differences, SVK's at zero strain") {
  const Mat3 gCov = someMetric(), gCon = gCov.inverse();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (int trial = 0; trial < 5; ++trial) {
    Vec6 E;
    for (int p = 0; p < 6; ++p) E(p) = u(rng);
    Vec6 s;
    Mat6 c;
    REQUIRE(std::isfinite(neoHookean(E, gCov, gCon, kLambda, kMu, s, &c)));
    Vec6 sFd;
    Mat6 cFd;
    const double h = 1e-6;
    for (int p = 0; p < 6; ++p) {
      Vec6 Ep = E, Em = E, sp, sm;
      Ep(p) += h;
      Em(p) -= h;
      sFd(p) = (neoHookean(Ep, gCov, gCon, kLambda, kMu, sp, nullptr) -
                neoHookean(Em, gCov, gCon, kLambda, kMu, sm, nullptr)) / (2 * h);
      cFd.col(p) = (sp - sm) / (2 * h);
    }
    CHECK((sFd - s).norm() <= 1e-7 * s.norm());
    CHECK((cFd - c).norm() <= 1e-7 * c.norm());
  }
  Vec6 s;
  Mat6 c;
  CHECK(neoHookean(Vec6::Zero(), gCov, gCon, kLambda, kMu, s, &c) == doctest::Approx(0).scale(1));
  CHECK(s.norm() <= 1e-10 * kMu);
  CHECK((c - svkTangent(gCon)).norm() <= 1e-12 * c.norm());
  // a section turned inside out (det C <= 0) has no energy
  Vec6 collapse = Vec6::Zero();
  collapse(2) = -0.5 * gCov(2, 2);  // C_33 = 0
  CHECK(std::isinf(neoHookean(collapse, gCov, gCon, kLambda, kMu, s, &c)));
}

TEST_CASE("neo-Hookean beam element: tangent against central differences") {
  for (auto kind : {GeometryKind::Line, GeometryKind::Helix})
    for (double fBend : {1.0, 0.12}) {
      CAPTURE(int(kind));
      CAPTURE(fBend);
      const Rod o = makeRod(MaterialLaw::NeoHookean, kind, 2, fBend);
      std::mt19937 rng(17);
      std::uniform_real_distribution<double> u(-0.05, 0.05);
      Eigen::VectorXd q = o.fs.qRef;
      for (Index i = 0; i < q.size(); ++i) q(i) += u(rng);
      for (Index e = 0; e < o.fs.elements(); ++e) {
        const ElementPoints pts = elementPoints(o.beams, e);
        ElementVector<2> qe = elementDofs<2>(q, o.fs, e), f, fp, fm, gFd;
        ElementMatrix<2> K, Kfd;
        REQUIRE(std::isfinite(beamElement<2>(pts, qe, f, &K)));
        const double h = 1e-6;
        for (int i = 0; i < kElementDofs<2>; ++i) {
          ElementVector<2> qp = qe, qm = qe;
          qp(i) += h;
          qm(i) -= h;
          const double Ep = beamElement<2>(pts, qp, fp, nullptr);
          const double Em = beamElement<2>(pts, qm, fm, nullptr);
          Kfd.col(i) = (fp - fm) / (2 * h);
          gFd(i) = (Ep - Em) / (2 * h);
        }
        CHECK((Kfd - K).norm() <= 1e-6 * K.norm());
        CHECK((gFd - f).norm() <= 1e-6 * f.norm());
        CHECK((K - K.transpose()).norm() <= 1e-12 * K.norm());
      }
    }
}

TEST_CASE("the neo-Hookean section is stress-free at the reference and has a law section per point") {
  for (auto kind : {GeometryKind::Line, GeometryKind::Helix}) {
    CAPTURE(int(kind));
    const Rod nh = makeRod(MaterialLaw::NeoHookean, kind, 2);
    const Rod svk = makeRod(MaterialLaw::SaintVenantKirchhoff, kind, 2);
    CHECK(nh.beams.lawSections.size() == nh.beams.z.size());
    CHECK(svk.beams.lawSections.empty());
    for (Index e = 0; e < nh.fs.elements(); ++e) {
      ElementVector<2> f;
      ElementMatrix<2> K;
      beamElement<2>(elementPoints(nh.beams, e), elementDofs<2>(nh.fs.qRef, nh.fs, e), f, &K);
      CHECK(f.norm() <= 1e-9 * K.norm());
    }
  }
}

TEST_CASE("a rod compressed past Saint Venant-Kirchhoff's turning point: the neo-Hookean closed form") {
  const double area = std::numbers::pi * 0.01;
  double previous = 0;
  for (double a : {0.9, 0.7, 0.5, 0.3}) {
    CAPTURE(a);
    const Uniaxial u = uniaxialNeoHookean(a);
    const EndForce nh = homogeneousStretch(MaterialLaw::NeoHookean, a, u.t);
    CHECK(nh.axial == doctest::Approx(u.P * area).epsilon(1e-9));
    CHECK(nh.directors <= 1e-9 * std::abs(nh.axial));  // the section is free: uniaxial stress
    CHECK(nh.axial < previous);  // more compression, more force
    previous = nh.axial;
  }
  // Saint Venant-Kirchhoff, same rod, section held at its size, turns back: its compressive
  // force at stretch 0.3 is smaller than at 0.5 (the nominal stress (lambda + 2 mu)(a^2 - 1) a / 2
  // peaks at a = 1/sqrt(3)), which is what lets a tightly bent beam fold.
  const double at5 = homogeneousStretch(MaterialLaw::SaintVenantKirchhoff, 0.5, 1).axial;
  const double at3 = homogeneousStretch(MaterialLaw::SaintVenantKirchhoff, 0.3, 1).axial;
  CHECK(at3 > at5);
}

TEST_CASE("a thick rod rolled up to R kappa = 0.63: neo-Hookean bends on, Saint Venant-Kirchhoff turns back") {
  // L = 1 mm, R = 0.1 mm, 20 quadratic elements, an end moment 2 pi EI / L (a full circle for a
  // linear moment-curvature law, R kappa = 0.63). Saint Venant-Kirchhoff's moment has a maximum
  // near R kappa = 0.42 (its inner fibres soften below the stretch 1/sqrt(3)): load control stops
  // there. Neo-Hookean carries the moment; pure bending bends the rod into a uniform arc.
  const auto rollUp = [](MaterialLaw law) {
    test::BeamSpec b;
    b.length = 1;
    b.radius = 0.1;
    b.elements = 20;
    b.law = law;
    b.integration.axial = AxialRule::Full;
    SceneDef s = test::straightBeam(b, 20);
    test::clampStart(s);
    test::tipLoad(s, LoadKind::Moment, Vec3(0, 0, 2 * std::numbers::pi * test::bendingStiffness(b) / b.length));
    auto w = std::make_unique<World>(s);
    const bool solved = test::solveAll(*w);
    return std::pair{std::move(w), solved};
  };
  const auto [svk, svkSolved] = rollUp(MaterialLaw::SaintVenantKirchhoff);
  CHECK_FALSE(svkSolved);
  CHECK(svk->time() < 0.7);
  const auto [nh, nhSolved] = rollUp(MaterialLaw::NeoHookean);
  REQUIRE(nhSolved);
  // the curvature of every element-end chord triple (circumcircle of nodes n, n+2, n+4) from
  // 2R off the clamp on (the clamped section cannot contract: a boundary layer about R long,
  // where the curvature is 0.2% lower)
  const Eigen::VectorXd& q = nh->fibres().q;
  std::vector<double> kappa;
  for (Index n = 8; n + 4 < nh->fibres().nodes(); n += 2) {
    const Vec3 a = x0Of(q, n), b = x0Of(q, n + 2), c = x0Of(q, n + 4);
    kappa.push_back(2 * (b - a).cross(c - a).norm() / ((b - a).norm() * (c - b).norm() * (c - a).norm()));
  }
  const auto [lo, hi] = std::minmax_element(kappa.begin(), kappa.end());
  MESSAGE("neo-Hookean roll-up: R kappa from " << 0.1 * *lo << " to " << 0.1 * *hi);
  CHECK(*hi - *lo <= 1e-5 * *hi);
  CHECK(0.1 * *lo > 0.45);  // beyond Saint Venant-Kirchhoff's turning point
}
