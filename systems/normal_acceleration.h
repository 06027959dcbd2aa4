// Loop B accelerated: Anderson mixing (systems/anderson_mixing.h) of the fibre-fibre contact
// normals over the passes of loops B and A within an increment (contact `normal_acceleration`,
// docs/CONTACT.md).
//
// Loop B is the fixed point N = G(N): Newton with the elements and normals N fixed gives a state
// q(N), eqs. 10-11 at q(N) give G(N). On a fibre lying on a parallel fibre under a vertical line
// load q (N/mm) the lateral mode has a gain ~ q / (2 R K) per pass (K: the lateral stiffness of
// the fibre with N fixed, N/mm^2): a normal tilted by phi pushes the fibre sideways by q phi / K,
// and the normal at the new state is tilted by that over 2 R. Above a gain of 1 the plain
// iteration diverges (line_contact_heavy: ~1000 at t = 0.6), whatever the relaxation; the mixed
// iterate N_{k+1} = G(N_k) - dG gamma (the secant over the last passes) converges to the fixed
// point, which is the equilibrium "normal_update" "newton" reaches.
// Every update of the increment is recorded (the normals N_k a pass solved with, G(N_k) after
// it), also the last of a loop B that met its tolerance, and the history goes on through loop A's
// next passes while the contact set is the same elements (same count and fibre pairs, sections
// within `reach` mm of the previous set's: 1e-2 R_min; fibres sliding along each other start it
// again). The mixed iterate replaces an update only once the map has shown itself unstable: an
// update turned the normals more than kGrowth = 100 times further than the one before (growth
// from a turn below 1e-9 rad, round-off, is not counted). Then the
// part of the step that the secant cannot explain is limited to kProbeTurn = 1e-5 rad per normal:
//   N_{k+1} = xBar + beta fBar,  beta = min(1, 1e-5 / max |fBar|)  (systems/anderson_mixing.h),
// since a plain step from a residual r lands ~ g r away, out of the secant's linear range (from
// 3.5e-4 rad to 0.14 rad at g = 400). A contraction (turns that shrink, or grow less than 100x,
// as friction switching and penalty updates make them in bundles) keeps the plain update: mixing
// it cost the squeezed 7-fibre bundle 5-14% more iterations. Measured (docs/RESULTS.md): the
// reduced line_contact_heavy (6 mm) converges to the straight state; the full case gets from
// t = 0.425 to 0.7 and fails there, because each increment's first detection is a plain step.
//
// Reads  FibreStore, the state q, ContactParams (forced normals, normal update), the particles
//        normals and forced signs of ContactElementStore (a forced element keeps N = +-D).
// Writes ContactElementStore::normal (the mixed normals, each renormalised), gap (gN = (xI - xJ).N
//        at q, mm) and gRev0 (projected on the new tangent plane, mm) of the loop's elements.
// Threading: parallel over elements, each writing its own entries (the mixing itself is serial,
// in element order: deterministic).
// The loop's elements: those whose normal is fixed in a Newton pass and given by eqs. 10-11 (not
// forced, which are constant, and not linearised in Newton, which already are the state's).
#pragma once

#include "components/contact.h"
#include "components/contact_params.h"
#include "components/fibres.h"
#include "systems/anderson_mixing.h"

#include <Eigen/Core>

#include <vector>

namespace fibra {

class NormalMixer {
 public:
  explicit NormalMixer(int memory) : mixer_(memory), on_(memory > 0) {}

  // After a detection: the contact set of the next passes. The history is kept when its loop
  // elements are the previous set's (same count and fibre pairs, sections within reach mm),
  // else started again.
  void follow(const ContactParams& p, const ContactElementStore& el, double reach);

  // A Newton pass starts with these normals N_k.
  void solving(const ContactElementStore& el) { used_ = stacked(el); }

  // After the update (el.normal = G(N_k)): the pair recorded; true when a secant step (the mixed
  // iterate) is prepared for apply(), false when the plain update stands.
  bool record(const ContactElementStore& el);

  // The prepared iterate put in place of the update, with the gaps at q and g_rev,0 to match.
  void apply(const FibreStore& fs, const Eigen::VectorXd& q, ContactElementStore& el) const;

  // Whether an update since the last change of elements turned the normals kGrowth x further
  // than the one before (the fixed point diverges).
  bool unstable() const { return unstable_; }

 private:
  Eigen::VectorXd stacked(const ContactElementStore& el) const;

  AndersonMixer mixer_;
  bool on_;
  std::vector<Index> which_;       // the loop's elements, ascending
  std::vector<Index> pairI_, pairJ_;
  std::vector<double> sI_, sJ_;    // their sections, mm
  Eigen::VectorXd used_;           // the normals of the last pass, stacked (3 per element)
  Eigen::VectorXd mixed_;          // the prepared iterate (unit normals)
  double lastTurn_ = 0;            // largest |G(N) - N| component of the last update
  bool unstable_ = false;          // an update turned the normals > kGrowth x the one before
};

// The elements loop B iterates on (see above), ascending.
std::vector<Index> loopNormalElements(const ContactParams& p, const ContactElementStore& el);

}  // namespace fibra
