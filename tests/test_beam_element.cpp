// Beam element: exact gradient and tangent against central finite differences, rigid-motion
// invariance, on straight and helical references, both orders and all integration rules.
#include "engine/fibre_builder.h"
#include "systems/beam_element.h"
#include "systems/beam_section.h"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>

using namespace fibra;

namespace {

struct OneFibre {
  FibreStore fs;
  MaterialStore mats;
  BeamStore beams;
};

OneFibre makeFibre(GeometryKind kind, int order, BeamIntegration integ, double fBend = 1) {
  OneFibre o;
  o.mats.law = {MaterialLaw::SaintVenantKirchhoff};
  o.mats.name = {"m"};
  o.mats.youngModulus = {4000};
  o.mats.poissonRatio = {0.3};
  o.mats.bendingFactor = {fBend};
  o.mats.torsionFactor = {0.7};
  FibreDef def;
  def.name = "f";
  def.radius = 0.1;
  def.elements = 3;
  def.order = order;
  if (kind == GeometryKind::Line) {
    def.geometry.points = {Vec3(0, 0, 0), Vec3(1.5, 0.3, -0.2)};
  } else {
    def.geometry.kind = GeometryKind::Helix;
    def.geometry.helixRadius = 0.4;
    def.geometry.pitch = 1.2;
    def.geometry.turns = 0.4;
    def.geometry.phase = 0.3;
  }
  addFibre(o.fs, def, 0, "fibres[0]");
  buildBeamReference(o.fs, o.mats, {integ}, o.beams);
  return o;
}

template <int Order>
ElementVector<Order> elementDofs(const Eigen::VectorXd& q, const FibreStore& fs, Index e) {
  return q.segment<kElementDofs<Order>>(kNodeDofs * fs.elementFirstNode[e]);
}

// A large random deformation: rotation, stretch and per-DOF noise.
Eigen::VectorXd deformed(const FibreStore& fs, unsigned seed, double noise) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd q = fs.qRef;
  for (Index i = 0; i < q.size(); ++i) q(i) += noise * u(rng);
  return q;
}

template <int Order>
void checkDerivatives(const OneFibre& o, unsigned seed) {
  const Eigen::VectorXd q = deformed(o.fs, seed, 0.15);
  for (Index e = 0; e < o.fs.elements(); ++e) {
    const ElementPoints pts = elementPoints(o.beams, e);
    ElementVector<Order> qe = elementDofs<Order>(q, o.fs, e), f, fp, fm;
    ElementMatrix<Order> K, Kfd, dummy;
    beamElement<Order>(pts, qe, f, &K);
    ElementVector<Order> gfd;
    const double h = 1e-6;
    for (int i = 0; i < kElementDofs<Order>; ++i) {
      ElementVector<Order> qp = qe, qm = qe;
      qp(i) += h;
      qm(i) -= h;
      const double Ep = beamElement<Order>(pts, qp, fp, &dummy);
      const double Em = beamElement<Order>(pts, qm, fm, &dummy);
      Kfd.col(i) = (fp - fm) / (2 * h);
      gfd(i) = (Ep - Em) / (2 * h);
    }
    CHECK((Kfd - K).norm() <= 1e-6 * K.norm());
    CHECK((gfd - f).norm() <= 1e-6 * f.norm());
    CHECK((K - K.transpose()).norm() <= 1e-12 * K.norm());
  }
}

}  // namespace

TEST_CASE("beam element tangent matches central finite differences") {
  for (auto kind : {GeometryKind::Line, GeometryKind::Helix})
    for (auto axial : {AxialRule::Reduced, AxialRule::Full})
      for (auto section : {SectionRule::Moments, SectionRule::Quadrature}) {
        CAPTURE(int(kind));
        CAPTURE(int(axial));
        CAPTURE(int(section));
        const BeamIntegration integ{axial, section, 3, 8};
        checkDerivatives<2>(makeFibre(kind, 2, integ), 7);
        checkDerivatives<1>(makeFibre(kind, 1, integ), 11);
        checkDerivatives<2>(makeFibre(kind, 2, integ, 0.12), 13);
      }
}

TEST_CASE("rigid motions give zero energy and force, rotation keeps the energy") {
  for (auto kind : {GeometryKind::Line, GeometryKind::Helix}) {
    const OneFibre o = makeFibre(kind, 2, {AxialRule::Full, SectionRule::Quadrature, 3, 8});
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(1.1, Vec3(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
    const Vec3 shift(2, -1, 0.5);
    auto moved = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd out = q;
      for (Index n = 0; n < o.fs.nodes(); ++n) {
        x0Of(out, n) = R * x0Of(q, n) + shift;
        g1Of(out, n) = R * g1Of(q, n);
        g2Of(out, n) = R * g2Of(q, n);
      }
      return out;
    };
    const Eigen::VectorXd qRigid = moved(o.fs.qRef);
    const Eigen::VectorXd qDef = deformed(o.fs, 3, 0.1), qDefRot = moved(qDef);
    for (Index e = 0; e < o.fs.elements(); ++e) {
      const ElementPoints pts = elementPoints(o.beams, e);
      ElementVector<2> f, f0;
      const double Erigid = beamElement<2>(pts, elementDofs<2>(qRigid, o.fs, e), f, nullptr);
      const double Edef = beamElement<2>(pts, elementDofs<2>(qDef, o.fs, e), f0, nullptr);
      const double Erot = beamElementEnergy<2>(pts, elementDofs<2>(qDefRot, o.fs, e));
      CHECK(std::abs(Erigid) <= 1e-12 * Edef);
      CHECK(f.norm() <= 1e-10 * f0.norm());
      CHECK(Erot == doctest::Approx(Edef).epsilon(1e-12));
    }
  }
}

TEST_CASE("reduced integration adds no zero-energy mode: a free fibre has exactly six") {
  for (auto kind : {GeometryKind::Line, GeometryKind::Helix})
    for (int order : {1, 2}) {
      CAPTURE(int(kind));
      CAPTURE(order);
      const OneFibre o = makeFibre(kind, order, {AxialRule::Reduced, SectionRule::Moments, 3, 8});
      const Index n = kNodeDofs * o.fs.nodes();
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
      for (Index e = 0; e < o.fs.elements(); ++e) {
        const Index d0 = kNodeDofs * o.fs.elementFirstNode[e];
        const ElementPoints pts = elementPoints(o.beams, e);
        if (order == 2) {
          ElementVector<2> f;
          ElementMatrix<2> Ke;
          beamElement<2>(pts, elementDofs<2>(o.fs.qRef, o.fs, e), f, &Ke);
          K.block<27, 27>(d0, d0) += Ke;
        } else {
          ElementVector<1> f;
          ElementMatrix<1> Ke;
          beamElement<1>(pts, elementDofs<1>(o.fs.qRef, o.fs, e), f, &Ke);
          K.block<18, 18>(d0, d0) += Ke;
        }
      }
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
      const double tol = 1e-9 * ev.maxCoeff();
      CHECK((ev.array().abs() < tol).count() == 6);
      CHECK(ev(6) > 1e3 * tol);  // the seventh mode is clearly stiff
    }
}
