// Stick and slip within a Newton pass (systems/friction_status.h): the law with a held branch
// (force and tangent against central differences, the two branches meeting on the slip
// circle), the counting of branch changes that holds an element, and the end-of-pass check that
// switches a held element found on the wrong side of the circle.
#include "systems/friction_status.h"
#include "fd_tangent.h"

#include <doctest/doctest.h>

#include <Eigen/Geometry>

using namespace fibra;

namespace {

const ContactLawParams kLaw{400, 2e-4, 0.2, 5e-4};  // k N/mm, p_reg mm, mu, g_max mm

ContactLawState lawState() {
  ContactLawState s;
  s.normal = Vec3(0.2, -0.3, 1).normalized();
  s.d0 = Vec3(0.01, 0.02, 0);
  return s;
}

// Relative position with gap g and a trial slip of length ratio x g_max (gRev0 = 0).
Vec3 positionAt(const ContactLawState& s, double g, double ratio) {
  const Vec3 t = s.normal.cross(Vec3::UnitX()).normalized();
  return s.d0 + (g - s.d0.dot(s.normal)) * s.normal + ratio * kLaw.gMax * t;
}

double tangential(const ContactLawResult& r, const Vec3& N) {
  return (r.force - r.force.dot(N) * N).norm();
}

void checkTangent(const Vec3& d, const ContactLawState& s, std::uint8_t hold) {
  CHECK(test::lawTangentError(d, s, kLaw, hold) <= 1e-6);
}

ContactLawResult lawResult(bool slip, double ratio) {
  ContactLawResult r;
  r.normalForce = ratio > 0 ? 1 : 0;
  r.slip = slip;
  r.trialRatio = ratio;
  return r;
}

}  // namespace

TEST_CASE("a held branch gives its own force and a consistent tangent on the wrong side of the circle") {
  const ContactLawState s = lawState();
  const double g = -3e-4;
  // Held in stick outside the circle: the elastic force goes on growing past mu R_N.
  const Vec3 outside = positionAt(s, g, 1.5);
  const ContactLawResult stick = contactLaw(outside, s, kLaw, false, kStatusStick);
  CHECK_FALSE(stick.slip);
  CHECK(stick.trialRatio == doctest::Approx(1.5));
  CHECK(tangential(stick, s.normal) == doctest::Approx(1.5 * kLaw.mu * stick.normalForce));
  checkTangent(outside, s, kStatusStick);
  // Held in slip inside the circle: Coulomb's mu R_N along the trial slip.
  const Vec3 inside = positionAt(s, g, 0.5);
  const ContactLawResult slip = contactLaw(inside, s, kLaw, false, kStatusSlip);
  CHECK(slip.slip);
  CHECK(tangential(slip, s.normal) == doctest::Approx(kLaw.mu * slip.normalForce));
  checkTangent(inside, s, kStatusSlip);
  // Free, the return mapping decides as before.
  CHECK(contactLaw(outside, s, kLaw, false).slip);
  CHECK_FALSE(contactLaw(inside, s, kLaw, false).slip);
  // On the circle the two branches give the same force (the error of a held branch is its
  // distance from the circle).
  const Vec3 on = positionAt(s, g, 1.0);
  const Vec3 a = contactLaw(on, s, kLaw, false, kStatusStick).force;
  const Vec3 b = contactLaw(on, s, kLaw, false, kStatusSlip).force;
  CHECK((a - b).norm() <= 1e-12 * a.norm());
}

TEST_CASE("an element is held after friction_hold_after branch changes with the tangent") {
  FrictionStatusStore s;
  sizeFrictionStatus(s, 2);
  // Element 0: stick, slip, stick at assemblies with the tangent; residual-only evaluations
  // between them (a line search's trials) do not count.
  trackFrictionStatus(s, 0, lawResult(false, 0.9), true, 2);
  trackFrictionStatus(s, 0, lawResult(true, 1.2), false, 2);
  trackFrictionStatus(s, 0, lawResult(true, 1.1), true, 2);
  CHECK(s.held[0] == kStatusNone);
  CHECK(s.flips[0] == 1);
  trackFrictionStatus(s, 0, lawResult(false, 0.95), true, 2);
  CHECK(s.held[0] == kStatusStick);
  CHECK(s.trialRatio[0] == 0.95);
  // Element 1 with holding off: any number of changes, never held.
  for (int k = 0; k < 10; ++k) trackFrictionStatus(s, 1, lawResult(k % 2, 1), true, 0);
  CHECK(s.held[1] == kStatusNone);
  // A new pass keeps the held branch and forgets the counts; a new detection frees everything.
  openFrictionPass(s);
  CHECK(s.held[0] == kStatusStick);
  CHECK(s.flips[0] == 0);
  CHECK(s.last[0] == kStatusNone);
  clearFrictionStatus(s);
  CHECK(s.held[0] == kStatusNone);
  // A store of another size (a new contact set) starts free.
  s.held[0] = kStatusSlip;
  sizeFrictionStatus(s, 3);
  CHECK(s.held[0] == kStatusNone);
}

TEST_CASE("the end of a pass switches held elements off their branch by more than the tolerance") {
  FrictionStatusStore s;
  sizeFrictionStatus(s, 5);
  s.held = {kStatusStick, kStatusStick, kStatusSlip, kStatusSlip, kStatusNone};
  s.trialRatio = {1.005, 1.3, 0.98, 0.0, 3.0};  // element 3: no normal force now
  const HeldFriction before = heldFriction(s);
  CHECK(before.held == 4);
  CHECK(before.excess == doctest::Approx(0.3));
  CHECK(settleFrictionStatus(s, 0.01) == 2);  // elements 1 (stick at 1.3) and 2 (slip at 0.98)
  CHECK(s.held[0] == kStatusStick);
  CHECK(s.held[1] == kStatusSlip);
  CHECK(s.held[2] == kStatusStick);
  CHECK(s.held[3] == kStatusSlip);
  CHECK(s.held[4] == kStatusNone);
}
