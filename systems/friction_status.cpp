#include "systems/friction_status.h"

#include <algorithm>

namespace fibra {
namespace {

// How far element e's trial ratio is on the wrong side of the circle for its held branch.
double excessOf(const FrictionStatusStore& s, Index e) {
  const double r = s.trialRatio[e];
  if (r <= 0) return 0;  // no normal force: the branch does not matter
  if (s.held[e] == kStatusStick) return std::max(r - 1, 0.0);
  if (s.held[e] == kStatusSlip) return std::max(1 - r, 0.0);
  return 0;
}

}  // namespace

void sizeFrictionStatus(FrictionStatusStore& s, Index n) {
  if (s.size() == n) return;
  s.last.assign(n, kStatusNone);
  s.flips.assign(n, 0);
  s.held.assign(n, kStatusNone);
  s.trialRatio.assign(n, 0.0);
}

void clearFrictionStatus(FrictionStatusStore& s) {
  std::fill(s.last.begin(), s.last.end(), kStatusNone);
  std::fill(s.flips.begin(), s.flips.end(), 0);
  std::fill(s.held.begin(), s.held.end(), kStatusNone);
  std::fill(s.trialRatio.begin(), s.trialRatio.end(), 0.0);
}

void openFrictionPass(FrictionStatusStore& s) {
  std::fill(s.last.begin(), s.last.end(), kStatusNone);
  std::fill(s.flips.begin(), s.flips.end(), 0);
}

void trackFrictionStatus(FrictionStatusStore& s, Index e, const ContactLawResult& r,
                         bool withTangent, int maxFlips) {
  s.trialRatio[e] = r.trialRatio;
  if (!withTangent) return;
  const std::uint8_t now = r.trialRatio > 0 ? (r.slip ? kStatusSlip : kStatusStick) : kStatusNone;
  if (s.held[e] == kStatusNone && now != kStatusNone && s.last[e] != kStatusNone && now != s.last[e] &&
      maxFlips > 0 && ++s.flips[e] >= maxFlips)
    s.held[e] = now;
  s.last[e] = now;
}

Index settleFrictionStatus(FrictionStatusStore& s, double tol) {
  Index switched = 0;
  for (Index e = 0; e < s.size(); ++e) {
    if (excessOf(s, e) <= tol) continue;
    s.held[e] = s.held[e] == kStatusStick ? kStatusSlip : kStatusStick;
    ++switched;
  }
  return switched;
}

HeldFriction heldFriction(const FrictionStatusStore& s) {
  HeldFriction h;
  for (Index e = 0; e < s.size(); ++e) {
    if (s.held[e] == kStatusNone) continue;
    ++h.held;
    h.excess = std::max(h.excess, excessOf(s, e));
  }
  return h;
}

}  // namespace fibra
