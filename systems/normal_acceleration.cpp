#include "systems/normal_acceleration.h"

#include "systems/contact_geometry.h"
#include "systems/contact_params.h"
#include "systems/friction_history.h"
#include "systems/normal_linearisation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

// A mixed normal that turns further than this from the plain update G(N_k) (rad), or whose
// stacked vector is nearly zero, is not trusted: the pass keeps the plain update and the history
// starts again (the secant was fitted far from the fixed point).
constexpr double kMaxMixTurn = 0.5;
// An update that turns the normals more than kGrowth times further than the one before shows an
// unstable map (a gain of that order: ~400-1000 in line_contact_heavy; friction switching and
// penalty updates in a squeezed 7-fibre bundle give up to 10-100 and are left to the plain
// iteration, which converges there: mixing them cost 5-14% more iterations).
constexpr double kGrowth = 100;
// Growth from a turn below this (rad) is not counted: round-off growing into a first real update.
constexpr double kTurnFloor = 1e-9;
// Once the map is unstable, the largest turn of the part of a step the secant cannot explain, rad.
constexpr double kProbeTurn = 1e-5;

// The mixed normals made unit; false when one is not trusted (above).
bool normalise(Eigen::VectorXd& mixed, const Eigen::VectorXd& plain) {
  const double cosMax = std::cos(kMaxMixTurn);
  for (Index i = 0; i < Index(mixed.size() / 3); ++i) {
    auto n = mixed.segment<3>(3 * i);
    const double len = n.norm();
    if (!(len > 1e-3)) return false;
    n /= len;
    if (n.dot(plain.segment<3>(3 * i)) < cosMax) return false;
  }
  return true;
}

// Element e with the normal N: gN = (xI - xJ).N at q (mm), g_rev,0 on the plane normal to N.
void setNormal(const FibreStore& fs, const Eigen::VectorXd& q, Index e, const Vec3& N,
               ContactElementStore& el) {
  const Section I = contactSection(fs, q, el.fibreI[e], el.sI[e]);
  const Section J = contactSection(fs, q, el.fibreJ[e], el.sJ[e]);
  const Vec3 xI = I.x0 + el.xiI1[e] * I.g1 + el.xiI2[e] * I.g2;
  const Vec3 xJ = J.x0 + el.xiJ1[e] * J.g1 + el.xiJ2[e] * J.g2;
  el.normal[e] = N;
  el.gap[e] = (xI - xJ).dot(N);
  el.gRev0[e] = projectOnPlane(el.gRev0[e], N);
}

}  // namespace

std::vector<Index> loopNormalElements(const ContactParams& p, const ContactElementStore& el) {
  std::vector<Index> which;
  for (Index e = 0; e < el.size(); ++e)
    if (!linearisedNormal(p, el, e) && !el.forced[e])
      which.push_back(e);
  return which;
}

void NormalMixer::follow(const ContactParams& p, const ContactElementStore& el, double reach) {
  std::vector<Index> which = loopNormalElements(p, el);
  bool same = which.size() == which_.size() && used_.size() == Index(3 * which.size());
  for (std::size_t i = 0; same && i < which.size(); ++i) {
    const Index e = which[i];
    same = el.fibreI[e] == pairI_[i] && el.fibreJ[e] == pairJ_[i] &&
           std::abs(el.sI[e] - sI_[i]) <= reach && std::abs(el.sJ[e] - sJ_[i]) <= reach;
  }
  which_ = std::move(which);
  pairI_.resize(which_.size());
  pairJ_.resize(which_.size());
  sI_.resize(which_.size());
  sJ_.resize(which_.size());
  for (std::size_t i = 0; i < which_.size(); ++i) {
    const Index e = which_[i];
    pairI_[i] = el.fibreI[e], pairJ_[i] = el.fibreJ[e], sI_[i] = el.sI[e], sJ_[i] = el.sJ[e];
  }
  if (same) return;
  mixer_.reset();
  lastTurn_ = 0;
  unstable_ = false;
}

Eigen::VectorXd NormalMixer::stacked(const ContactElementStore& el) const {
  Eigen::VectorXd v(3 * which_.size());
  for (std::size_t i = 0; i < which_.size(); ++i) v.segment<3>(3 * i) = el.normal[which_[i]];
  return v;
}

bool NormalMixer::record(const ContactElementStore& el) {
  if (which_.empty()) return false;
  const Eigen::VectorXd plain = stacked(el);
  const double turn = (plain - used_).lpNorm<Eigen::Infinity>();
  unstable_ = unstable_ || (lastTurn_ > kTurnFloor && turn > kGrowth * lastTurn_);
  lastTurn_ = turn;
  if (!on_) return false;  // memory 0: instability only watched (unstable())
  const AndersonMixer::Split s = mixer_.split(used_, plain);
  if (mixer_.used() == 0 || !unstable_) return false;
  // The step along what the secant cannot explain, limited to a probe.
  const double unexplained = s.fBar.lpNorm<Eigen::Infinity>();
  mixed_ = s.xBar + std::min(1.0, kProbeTurn / std::max(unexplained, 1e-300)) * s.fBar;
  if (normalise(mixed_, plain)) return true;
  mixer_.reset();  // not trusted: a new history from this pair
  mixer_.split(used_, plain);
  return false;
}

void NormalMixer::apply(const FibreStore& fs, const Eigen::VectorXd& q,
                        ContactElementStore& el) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which_.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        setNormal(fs, q, which_[i], mixed_.segment<3>(3 * i), el);
                    });
}

}  // namespace fibra
