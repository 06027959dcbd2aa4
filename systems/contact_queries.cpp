#include "systems/contact_queries.h"

#include "systems/contact_geometry.h"
#include "systems/contact_normals.h"
#include "systems/contact_params.h"
#include "systems/contact_sections.h"
#include "systems/facing_particles.h"
#include "systems/particle.h"
#include "systems/tool_geometry.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fibra {

double stepLimit(const ContactParams& p, const ContactState& s, const Eigen::VectorXd& dq) {
  double a = 1;
  const auto limit = [&](double gap, double pMax, double dg) {
    const double allowed = p.stepPenetration * pMax;
    if (dg < 0) a = std::min(a, std::max(gap + allowed, allowed) / -dg);
  };
  const ContactElementStore& el = s.elements;
  // The gap's change along the particles the normal force acted on (an element on facing
  // particles: theirs, systems/facing_particles.h, whose weights are dg/dq).
  for (Index e = 0; e < el.size(); ++e)
    limit(s.forces.gap[e], s.zones.pMax[el.zone[e]],
          el.normal[e].dot(particlePosition(dq, forceParticle(el, s.forces, e, 0)) -
                           particlePosition(dq, forceParticle(el, s.forces, e, 1))));
  const ToolContactStore& t = s.toolElements;
  for (Index i = 0; i < t.size(); ++i)
    limit(s.toolForces.gap[i], s.toolZones.pMax[t.zone[i]],
          t.normal[i].dot(particlePosition(dq, t.side[i])));
  return a;
}

double deepestDetected(const ContactState& s) {
  double d = 0;
  for (Index e = 0; e < s.elements.size(); ++e)
    d = std::max(d, -s.elements.gap[e] / s.zones.pMax[s.elements.zone[e]]);
  for (Index i = 0; i < s.toolElements.size(); ++i)
    d = std::max(d, -s.toolElements.gap[i] / s.toolZones.pMax[s.toolElements.zone[i]]);
  return d;
}

void fillContactReport(const ContactParams& p, const ContactState& s, ContactReport& r) {
  r.zones = s.zones.size();
  r.refinedZones = Index(std::count(s.zones.refined.begin(), s.zones.refined.end(), 1));
  r.elements = s.elements.size();
  r.toolElements = s.toolElements.size();
  r.active = r.sliding = 0;
  r.maxPenetration = r.maxPenetrationRatio = 0;
  const auto add = [&](const ContactForceStore& f, Index e, double pMax) {
    r.active += f.normalForce[e] > 0;
    r.sliding += sliding(f.normalForce[e], f.gRev[e], p.gMax);
    r.maxPenetration = std::max(r.maxPenetration, -f.gap[e]);
    r.maxPenetrationRatio = std::max(r.maxPenetrationRatio, -f.gap[e] / pMax);
  };
  for (Index e = 0; e < s.elements.size(); ++e) add(s.forces, e, s.zones.pMax[s.elements.zone[e]]);
  for (Index i = 0; i < s.toolElements.size(); ++i)
    add(s.toolForces, i, s.toolZones.pMax[s.toolElements.zone[i]]);
}

ToolOverlap toolOverlap(const FibreStore& fibres, const Eigen::VectorXd& q, const ToolStore& tools,
                        Index tool, double time) {
  const RigidMotion m = toolMotion(tools, tool, time);
  ToolOverlap o;
  for (Index e = 0; e < fibres.elements(); ++e) {
    const double R = fibres.radius[fibres.elementFibre[e]];
    for (int k = 0; k <= kToolOverlapCuts; ++k) {
      const double z = -1 + 2.0 * k / kToolOverlapCuts;
      const Section S = sectionAt(fibres, q, {e, z});
      const SurfacePoint p = closestSurfacePoint(tools, tool, m, S.x0);
      const double depth = halfWidth(S, R, p.normal) - p.distance;
      if (depth > o.depth) o = {depth, e, z};
    }
  }
  return o;
}

double halfWidth(const Section& S, double R, const Vec3& n) {
  return R * std::hypot(S.g1.dot(n), S.g2.dot(n));
}

namespace {

// An end face's point x against the other fibre S (radius R): its depth below that fibre's
// surface, w - |P_t (x - x0)| (the centreline distance says nothing there: the face lies across it).
double faceDepth(const Section& S, double R, const Vec3& x) {
  const Vec3 t = S.dx0ds.normalized(), d = x - S.x0;
  const Vec3 radial = d - d.dot(t) * t;
  const double r = radial.norm();
  return r > 0 ? halfWidth(S, R, radial / r) - r : halfWidth(S, R, S.g1.normalized());
}

// The overlap of the discs of I at sI and J at sJ (mm; tubeOverlap below says why these two
// directions).
double discOverlap(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& params,
                   Index fI, double sI, Index fJ, double sJ) {
  const Section I = contactSection(fs, q, fI, sI), J = contactSection(fs, q, fJ, sJ);
  const double RI = fs.radius[fI], RJ = fs.radius[fJ];
  // The discs' overlap along n, w_I(n) + w_J(n) - (x0I - x0J).n, bounds their true overlap from
  // above for every unit n (their support functions): the least of two candidates. Across the
  // mean tangent t, n = P_t d / |P_t d| (d = x0I - x0J; coincident centres: I's first director),
  // normal to both fibres at closest points and the measure of parallel fibres whose sections lie
  // apart along them; and eq. 10's direction (systems/contact_normals.h), which for crossing
  // fibres is their common normal, or that of the segments they cover past an end (across the
  // mean tangent alone, a tilted end 0.005 mm clear of a crossing fibre read 27 p_max deep).
  const auto along = [&](const Vec3& n) {
    return halfWidth(I, RI, n) + halfWidth(J, RJ, n) - (I.x0 - J.x0).dot(n);
  };
  const Vec3 tI = I.dx0ds.normalized(), tJ = J.dx0ds.normalized();
  const Vec3 t = (tI + (tI.dot(tJ) < 0 ? Vec3(-tJ) : tJ)).normalized();
  Vec3 d = I.x0 - J.x0;
  if (const Vec3 across = d - d.dot(t) * t; across.norm() > 1e-9 * (RI + RJ)) d = across;
  const double dist = d.norm();
  const double acrossTangent = along(dist > 0 ? Vec3(d / dist) : Vec3(I.g1.normalized()));
  const NormalOf<double> n = normalOfSections<double>(
      I.x0, J.x0, I.dx0ds, J.dx0ds, I.x0, J.x0, I.g1, RI, RJ, params.thetaParallel,
      params.thetaCross, 0, endRoom(fs, q, fI, sI, fJ, sJ, params.thetaParallel));
  return std::min(acrossTangent, along(n.normal));
}

// The overlap of two fibres near the pair of sections (sI, sJ), mm: at the closest points of
// their centrelines within one element of the pair (closestSectionsNear: a minimum of the
// distance, or the distance still falling at a fibre's end, with the fibres not parallel;
// `seekClosest`), else at the pair. Where one section is an end of its fibre and the other
// centre lies beyond that end's plane, the end face's point closest to that centre against the
// other fibre (faceDepth: the rim pressed into its side, at the face's deepest point). Otherwise
// the least of the discs' overlaps along two directions (below), both normal to the fibres at
// closest points, so that R |G^T n| is each tube's width along them: a pair whose sections lie
// apart along the fibres is not measured along a direction that runs through a tube lengthwise
// (a sheared section is wider along such a direction than the tube is across it: 1.54 p_max
// read where the fibres crossed with 0.82, the plectoneme at t = 0.78, its sections near the
// clamp sheared 6.6 deg).
// sI, sJ (mm): in, the pair; out, where the overlap was measured.
double tubeOverlap(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                   const ContactParams& params, Index fI, Index fJ, double& sI, double& sJ,
                   bool seekClosest) {
  const double hI = elementLength(fs, fI), hJ = elementLength(fs, fJ);
  const SectionWindows window{std::max(0.0, sI - hI), std::min(fs.length[fI], sI + hI),
                              std::max(0.0, sJ - hJ), std::min(fs.length[fJ], sJ + hJ)};
  const double sep = fI == fJ ? params.selfSeparation[fI] : 0;
  if (seekClosest)
    closestSectionsNear(fs, cl, fI, fJ, window, params.thetaParallel, sep, sI, sJ);
  Section I = contactSection(fs, q, fI, sI), J = contactSection(fs, q, fJ, sJ);
  const double RI = fs.radius[fI], RJ = fs.radius[fJ];
  double xi[2];
  if (seekClosest && endFaceContact(fs, q, cl, fI, sI, I, fJ, sep, 0, sJ, J, xi))
    return faceDepth(J, RJ, I.x0 + xi[0] * I.g1 + xi[1] * I.g2);
  if (seekClosest && endFaceContact(fs, q, cl, fJ, sJ, J, fI, sep, 0, sI, I, xi))
    return faceDepth(I, RI, J.x0 + xi[0] * J.g1 + xi[1] * J.g2);
  double depth = discOverlap(fs, q, params, fI, sI, fJ, sJ);
  if (!seekClosest) return depth;
  // A kinked node is a minimum of the centreline distance that the Newton search above, on
  // smooth pieces, does not land on: each kink in the windows is measured against the other
  // fibre's point closest to it (element by element, so that a kink of the other fibre is found
  // too: a vertex on a vertex).
  const auto atKinks = [&](Index f, Index g, double lo, double hi, double glo, double ghi,
                           bool fIsI) {
    forEachKink(fs, q, f, lo, hi, params.thetaParallel, [&](Index, double sk) {
      double sg = fIsI ? sJ : sI;
      closestPointOnFibre(fs, cl, g, centrelineAt(fs, cl, f, sk).x, glo, ghi, sg);
      const double a = fIsI ? sk : sg, b = fIsI ? sg : sk;
      const double k = discOverlap(fs, q, params, fI, a, fJ, b);
      if (k > depth) depth = k, sI = a, sJ = b;
    });
  };
  atKinks(fI, fJ, window.aI, window.bI, window.aJ, window.bJ, true);
  atKinks(fJ, fI, window.aJ, window.bJ, window.aI, window.bI, false);
  return depth;
}

}  // namespace

namespace {

// Element e's true overlap at the state q (mm; negative: the fibres' clearance there), measured
// as trueOverlap says; sI, sJ receive where (reference arc lengths, mm).
double elementOverlap(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                      const ContactElementStore& el, Index e, const ContactParams& params,
                      double& sI, double& sJ) {
  const Index fI = el.fibreI[e], fJ = el.fibreJ[e];
  sI = el.sI[e], sJ = el.sJ[e];
  if (el.fallback[e] & (kEndFaceI | kEndFaceJ)) {
    const Section I = contactSection(fs, q, fI, sI), J = contactSection(fs, q, fJ, sJ);
    return el.fallback[e] & kEndFaceI
               ? faceDepth(J, fs.radius[fJ], I.x0 + el.xiI1[e] * I.g1 + el.xiI2[e] * I.g2)
               : faceDepth(I, fs.radius[fI], J.x0 + el.xiJ1[e] * J.g1 + el.xiJ2[e] * J.g2);
  }
  return tubeOverlap(fs, q, cl, params, fI, fJ, sI, sJ, !el.forced[e]) -
         forcedAllowance(params, el.forced[e]);
}

// Keeps in `o` the element e's figure `depth` (mm) if its ratio to the element's p_max is the
// largest so far.
void keepLargest(Overlap& o, const ContactState& s, Index e, double depth, double sI, double sJ) {
  const ContactElementStore& el = s.elements;
  o.depth = std::max(o.depth, depth);
  const double ratio = depth / s.zones.pMax[el.zone[e]];
  if (ratio <= o.ratio) return;
  o.ratio = ratio;
  o.fibreI = el.fibreI[e], o.fibreJ = el.fibreJ[e];
  o.sI = sI, o.sJ = sJ;
}

}  // namespace

Overlap trueOverlap(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                    const ContactState& detected, const ContactParams& params,
                    std::vector<double>* ratios) {
  const ContactElementStore& el = detected.elements;
  Overlap deepest;
  if (ratios) ratios->assign(std::size_t(el.size()), 0.0);
  for (Index e = 0; e < el.size(); ++e) {
    double sI, sJ;
    const double depth = elementOverlap(fs, q, cl, el, e, params, sI, sJ);
    if (ratios) (*ratios)[std::size_t(e)] = depth / detected.zones.pMax[el.zone[e]];
    keepLargest(deepest, detected, e, depth, sI, sJ);
  }
  return deepest;
}

namespace {

// The fibres' largest overlap near the pair (sI, sJ), mm (negative: their clearance): over the
// sections x_I(s) of I's window [sI - h_I, sI + h_I], each against the closest point of J's
// window [sJ - h_J, sJ + h_J] (closestPointOnFibre), the discs' overlap along the line between
// them, w_I + w_J - |d| (support functions: each a bound of the true overlap from above); the
// best of 33 samples, refined by golden-section search between its neighbours. Where the element
// stands for a crossing that lies between its Gauss points (eq. 10 measures the tangent lines'
// distance, not the sections'), the crossing is in the window. A pair that touches at s = sI is
// not searched further (only clearances are asked for: the overlap there is returned).
double nearestApproach(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                       Index fI, double sI, Index fJ, double sJ) {
  const double hI = elementLength(fs, fI), hJ = elementLength(fs, fJ);
  const double lo = std::max(0.0, sI - hI), hi = std::min(fs.length[fI], sI + hI);
  const double loJ = std::max(0.0, sJ - hJ), hiJ = std::min(fs.length[fJ], sJ + hJ);
  const double RI = fs.radius[fI], RJ = fs.radius[fJ];
  const auto overlapAt = [&](double s) {
    double sOther = sJ;
    closestPointOnFibre(fs, cl, fJ, centrelineAt(fs, cl, fI, s).x, loJ, hiJ, sOther);
    const Section I = contactSection(fs, q, fI, s), J = contactSection(fs, q, fJ, sOther);
    const Vec3 d = I.x0 - J.x0;
    const double dist = d.norm();
    const Vec3 n = dist > 0 ? Vec3(d / dist) : Vec3(I.g1.normalized());
    return halfWidth(I, RI, n) + halfWidth(J, RJ, n) - dist;
  };
  double best = overlapAt(sI), atI = sI;
  if (best >= 0) return best;
  const auto keep = [&](double s) {
    if (const double o = overlapAt(s); o > best) best = o, atI = s;
  };
  constexpr int kSamples = 32;
  for (int k = 0; k <= kSamples; ++k) keep(lo + (hi - lo) * k / kSamples);
  const double phi = (std::sqrt(5.0) - 1) / 2, step = (hi - lo) / kSamples;
  double a = std::max(lo, atI - step), b = std::min(hi, atI + step);
  for (int i = 0; i < 40 && b - a > 1e-9 * hI; ++i) {
    const double c = b - phi * (b - a), e = a + phi * (b - a);
    if (overlapAt(c) > overlapAt(e))
      b = e;
    else
      a = c;
  }
  keep(0.5 * (a + b));
  return best;
}

// Whether element e's fibres make less than thetaParallel (rad) at its sections: its normal is
// then the line of centres (eq. 10 without n_cross), and its gap the sections' own.
bool parallelAt(const FibreStore& fs, const Eigen::VectorXd& q, const ContactElementStore& el,
                Index e, double thetaParallel) {
  const Vec3 tI = contactSection(fs, q, el.fibreI[e], el.sI[e]).dx0ds.normalized();
  const Vec3 tJ = contactSection(fs, q, el.fibreJ[e], el.sJ[e]).dx0ds.normalized();
  return std::atan2(tI.cross(tJ).norm(), std::abs(tI.dot(tJ))) < thetaParallel;
}

}  // namespace

Overlap falseForce(const FibreStore& fs, const Eigen::VectorXd& q, const CentrelineStore& cl,
                   const ContactState& used, const ContactParams& params) {
  const ContactElementStore& el = used.elements;
  Overlap clearest;
  for (Index e = 0; e < el.size(); ++e) {
    if (el.forced[e] || e >= used.forces.size() || !(used.forces.normalForce[e] > 0)) continue;
    if (!parallelAt(fs, q, el, e, params.thetaParallel)) continue;
    double sI, sJ;
    const double depth =
        el.fallback[e] & (kEndFaceI | kEndFaceJ)
            ? elementOverlap(fs, q, cl, el, e, params, sI, sJ)
            : nearestApproach(fs, q, cl, el.fibreI[e], el.sI[e], el.fibreJ[e], el.sJ[e]);
    keepLargest(clearest, used, e, -depth, el.sI[e], el.sJ[e]);  // where the element pushes
  }
  return clearest;
}

namespace {

double shift(double ds, double dxi1, double dxi2, double R) {
  return std::sqrt(ds * ds + dxi1 * dxi1 + dxi2 * dxi2) / R;
}

// Element b's gap at the state fs.q as the solve measured its counterpart: between the facing
// particles along b's normal where the used element acted on facing particles
// (systems/facing_particles.h), else the detection's own (material particles), mm.
double freshGap(const FibreStore& fs, const ContactParams& p, const ContactElementStore& ef,
                Index b, bool facing) {
  FacingSide I, J;
  if (!facing || !facingSide(fs.q, ef.sideI[b], fs.radius[ef.fibreI[b]], -ef.normal[b], I) ||
      !facingSide(fs.q, ef.sideJ[b], fs.radius[ef.fibreJ[b]], ef.normal[b], J))
    return ef.gap[b];
  return (I.position - J.position).dot(ef.normal[b]) +
         forcedAllowance(p, ef.forced[b]);
}

}  // namespace

void compareContactSets(const FibreStore& fs, const ContactState& used, const ContactState& fresh,
                        const ContactParams& params, ContactReport& r) {
  const ZoneStore &zu = used.zones, &zf = fresh.zones;
  const ContactElementStore &eu = used.elements, &ef = fresh.elements;
  std::unordered_map<std::uint64_t, Index> usedZone;
  for (Index z = 0; z < zu.size(); ++z) usedZone.emplace(zu.id[z], z);
  r.redetectZoneChanges = 0;
  r.redetectGapChange = r.redetectParticleShift = 0;
  Index found = 0;  // used zones the fresh set has (by id)
  for (Index z = 0; z < zf.size(); ++z) {
    const auto it = usedZone.find(zf.id[z]);
    found += it != usedZone.end();
    if (it == usedZone.end() || zu.elementCount[it->second] != zf.elementCount[z]) {
      ++r.redetectZoneChanges;
      continue;
    }
    const Index o = it->second;
    for (Index k = 0; k < zf.elementCount[z]; ++k) {
      const Index a = zu.firstElement[o] + k, b = zf.firstElement[z] + k;
      const bool facing = a < Index(used.forces.facing.size()) && used.forces.facing[a];
      const double gap = freshGap(fs, params, ef, b, facing);
      if (std::min(gap, used.forces.gap[a]) >= 0) continue;  // open in both
      r.redetectGapChange =
          std::max(r.redetectGapChange, std::abs(gap - used.forces.gap[a]) / zu.pMax[o]);
      const double sI = shift(ef.sI[b] - eu.sI[a], ef.xiI1[b] - eu.xiI1[a],
                              ef.xiI2[b] - eu.xiI2[a], fs.radius[ef.fibreI[b]]);
      const double sJ = shift(ef.sJ[b] - eu.sJ[a], ef.xiJ1[b] - eu.xiJ1[a],
                              ef.xiJ2[b] - eu.xiJ2[a], fs.radius[ef.fibreJ[b]]);
      r.redetectParticleShift = std::max({r.redetectParticleShift, sI, sJ});
    }
  }
  r.redetectZoneChanges += int(zu.size() - found);  // used zones the fresh set lost
}

}  // namespace fibra
