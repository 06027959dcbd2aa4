// Contact-friction law: forces and consistent tangents against central finite differences on
// both penalty branches, in stick and in slip; Coulomb's bound in slip; the regularised penalty
// is C1 at -p_reg.
#include "systems/contact_law.h"
#include "fd_tangent.h"

#include <doctest/doctest.h>

#include <Eigen/Geometry>

using namespace fibra;

namespace {

ContactLawState state() {
  ContactLawState s;
  s.normal = Vec3(0.2, -0.3, 1).normalized();
  s.d0 = Vec3(0.01, 0.02, 0);
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - s.normal * s.normal.transpose();
  s.gRev0 = P * Vec3(1e-4, -2e-4, 3e-4);
  return s;
}

// A relative position with gap g and tangential offset dt (along a fixed tangent direction).
Vec3 positionAt(const ContactLawState& s, double g, double dt) {
  const Vec3 t = s.normal.cross(Vec3::UnitX()).normalized();
  return s.d0 + (g - s.d0.dot(s.normal)) * s.normal + dt * t;
}

void checkTangent(const Vec3& d, const ContactLawState& s, const ContactLawParams& p) {
  CHECK(test::lawTangentError(d, s, p) <= 1e-6);
}

}  // namespace

TEST_CASE("contact law tangent matches finite differences: penalty branches, stick, slip") {
  const ContactLawState s = state();
  ContactLawParams p{400, 2e-4, 0.2, 5e-4};
  struct Case {
    double gap, slide;
    bool slip;
  };
  for (const Case c : {Case{-1e-4, 1e-5, false}, Case{-5e-4, 1e-5, false},
                       Case{-1e-4, 2e-3, true}, Case{-6e-4, -3e-3, true}}) {
    CAPTURE(c.gap);
    CAPTURE(c.slide);
    const Vec3 d = positionAt(s, c.gap, c.slide);
    const ContactLawResult r = contactLaw(d, s, p, false);
    CHECK(r.slip == c.slip);
    CHECK(r.gap == doctest::Approx(c.gap).scale(0));
    checkTangent(d, s, p);
    const double tangential = (r.force - r.force.dot(s.normal) * s.normal).norm();
    if (c.slip) CHECK(tangential == doctest::Approx(p.mu * r.normalForce).scale(0));
    else CHECK(tangential < p.mu * r.normalForce);
  }
  // Frictionless: the tangent is symmetric and only normal.
  p.mu = 0;
  const ContactLawResult r = contactLaw(positionAt(s, -3e-4, 1e-3), s, p, false);
  CHECK((r.stiffness - r.stiffness.transpose()).norm() <= 1e-14 * r.stiffness.norm());
  CHECK((r.force.cross(s.normal)).norm() < 1e-15);
}

TEST_CASE("no force and no stiffness when the gap is open") {
  const ContactLawState s = state();
  const ContactLawResult r = contactLaw(positionAt(s, 1e-4, 0), s, {400, 2e-4, 0.2, 5e-4}, false);
  CHECK(r.normalForce == 0);
  CHECK(r.force.norm() == 0);
  CHECK(r.stiffness.norm() == 0);
  CHECK(r.gRev.norm() == 0);
}

TEST_CASE("regularised penalty is continuous with a continuous slope at -p_reg and 0") {
  const double k = 300, pReg = 1e-4, e = 1e-12;
  double R1, d1, R2, d2;
  penaltyForce(-pReg + e, k, pReg, R1, d1);
  penaltyForce(-pReg - e, k, pReg, R2, d2);
  CHECK(R1 == doctest::Approx(R2).epsilon(1e-6).scale(0));
  CHECK(d1 == doctest::Approx(d2).epsilon(1e-6));
  CHECK(R1 == doctest::Approx(k * pReg / 2).scale(0));
  penaltyForce(-e, k, pReg, R1, d1);
  CHECK(std::abs(R1) < 1e-15);
  CHECK(std::abs(d1) <= 1.0001 * k * e / pReg);  // slope -> 0 at the touching point
}
