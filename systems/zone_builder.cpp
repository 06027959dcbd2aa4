#include "systems/zone_builder.h"

#include "core/columns.h"

#include "systems/contact_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace fibra {
namespace {

constexpr Index kFibreChunk = 4;  // fibres per output chunk (fixed: deterministic output)

void closeRun(ZonePartner& P) {
  if (P.open) P.zones.push_back(P.run);
  P.open = false;
}

ZonePartner& partnerOf(ZoneScratch& S, Index fibre) {
  Index& slot = S.slotOfFibre[fibre];
  if (slot < 0) {
    if (S.active == Index(S.partners.size())) S.partners.emplace_back();
    slot = S.active++;
    ZonePartner& P = S.partners[slot];
    P.fibre = fibre;
    P.lastElement = P.currentElement = -1;
    P.open = false;
    P.candidates.clear();
    P.zones.clear();
  }
  return S.partners[slot];
}

// Squared distance from x to a box (0 inside), mm^2: a lower bound of the distance to the
// element it bounds.
double pointBoxDistance2(const BoxD& b, const Vec3& x) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max(std::max(b.lo[k] - x[k], x[k] - b.hi[k]), 0.0);
    d2 += d * d;
  }
  return d2;
}

// A lower bound of the squared distance from x to the element: distance to its chord
// x(-1) x(1) less the largest deviation |c (z^2 - 1)| <= |c| of the element from its chord.
double chordBound2(const CentrelinePolynomial& P, const Vec3& x) {
  const Vec3 p0 = P.a - P.b + P.c, u = 2 * P.b;
  const double uu = u.squaredNorm();
  const double t = uu > 0 ? std::clamp((x - p0).dot(u) / uu, 0.0, 1.0) : 0.0;
  const double d = (p0 + t * u - x).norm() - P.c.norm();
  return d > 0 ? d * d : 0;
}

// Closest point of the candidates of P to x (within Delta_prox, else found = false).
struct Projection {
  bool found = false;
  double dist2, s;
};

Projection project(const FibreStore& fs, const ContactParams& p, const CentrelineStore& cl,
                   const ZonePartner& P, const Vec3& x, double s, double delta2, bool self) {
  const Index J = P.fibre, firstJ = fs.firstElement[J];
  const double hJ = elementLength(fs, J);
  const double tMin = self ? (s + p.selfSeparation[J]) / hJ : 0;  // self: s' >= s + separation
  Projection best{false, delta2, 0};
  for (const Index b : P.candidates) {
    if (pointBoxDistance2(cl.hull[b], x) > best.dist2) continue;
    if (chordBound2(cl.poly[b], x) > best.dist2) continue;
    double z0 = -1;
    if (self) {
      z0 = 2 * (tMin - (b - firstJ)) - 1;
      if (z0 > 1) continue;
      z0 = std::max(z0, -1.0);
    }
    const ClosestPoint c = closestOnPolynomial(cl.poly[b], x, z0, 1);
    const double sb = (b - firstJ + 0.5 * (c.z + 1)) * hJ;
    if (c.dist2 < best.dist2 || (c.dist2 == best.dist2 && (!best.found || sb < best.s)))
      best = {true, c.dist2, sb};
  }
  return best;
}

// Squared distance between two boxes (0 when they overlap), mm^2.
double boxBoxDistance2(const BoxD& a, const BoxD& b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max(std::max(a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]), 0.0);
    d2 += d * d;
  }
  return d2;
}

// Whether some candidate's box comes within sqrt(limit2) of element eI's box.
bool anyWithin(const CentrelineStore& cl, Index eI, const std::vector<Index>& candidates,
               double limit2) {
  for (const Index b : candidates)
    if (boxBoxDistance2(cl.hull[eI], cl.hull[b]) <= limit2) return true;
  return false;
}

// Runs the test points of element eI of fibre I against partner P, extending or closing its
// run. The first point (shared with eI - 1) is skipped when eI - 1 already tested it.
std::int64_t runTestPoints(const FibreStore& fs, const ContactParams& p,
                           const CentrelineStore& cl, Index I, Index eI, ZonePartner& P) {
  const Index J = P.fibre;
  const int m = testIntervalsPerElement(fs, p, I, J);
  const double l = elementLength(fs, I) / m;
  const double delta = proximityDistance(p, I, J);
  const Index i = eI - fs.firstElement[I];
  int k0 = 0;
  if (eI > fs.firstElement[I] && P.lastElement == eI - 1)
    k0 = 1;
  else
    closeRun(P);
  if (!anyWithin(cl, eI, P.candidates, delta * delta)) {  // no test point of eI can be proximate
    closeRun(P);
    P.lastElement = eI;
    return 0;
  }
  const CentrelinePolynomial& PI = cl.poly[eI];
  for (int k = k0; k <= m; ++k) {
    const double z = -1 + 2.0 * k / m;
    const Vec3 x = PI.a + z * (PI.b + z * PI.c);
    const double s = double(std::int64_t(i) * m + k) * l;
    const Projection pr = project(fs, p, cl, P, x, s, delta * delta, I == J);
    if (!pr.found) {
      closeRun(P);
      continue;
    }
    const double d = std::sqrt(pr.dist2);
    if (!P.open) {
      P.open = true;
      P.run = {I, J, s, s, pr.s, pr.s, d, 1};
    } else {
      P.run.sI2 = s;
      P.run.sJ2 = pr.s;
      P.run.minDistance = std::min(P.run.minDistance, d);
      ++P.run.testPoints;
    }
  }
  P.lastElement = eI;
  return m + 1 - k0;
}

// The zones of fibre I with all its partners J >= I, appended to `out` by (J, sI1).
std::int64_t buildFibre(const FibreStore& fs, const ContactParams& p, const CentrelineStore& cl,
                        const BroadphaseCache& bc, Index I, ZoneScratch& S,
                        std::vector<ZoneRecord>& out) {
  std::int64_t tested = 0;
  S.active = 0;
  const Index e0 = fs.firstElement[I], e1 = e0 + fs.elementCount[I];
  for (Index eI = e0; eI < e1; ++eI) {
    S.touched.clear();
    for (Index c = bc.candidateFirst[eI]; c < bc.candidateFirst[eI + 1]; ++c) {
      const Index B = bc.candidate[c];
      ZonePartner& P = partnerOf(S, fs.elementFibre[B]);
      if (P.currentElement != eI) {
        P.currentElement = eI;
        P.candidates.clear();
        S.touched.push_back(S.slotOfFibre[P.fibre]);
      }
      P.candidates.push_back(B);
    }
    for (const Index slot : S.touched) tested += runTestPoints(fs, p, cl, I, eI, S.partners[slot]);
  }
  S.order.resize(S.active);
  for (Index k = 0; k < S.active; ++k) S.order[k] = k;
  std::sort(S.order.begin(), S.order.end(),
            [&](Index a, Index b) { return S.partners[a].fibre < S.partners[b].fibre; });
  for (const Index slot : S.order) {
    ZonePartner& P = S.partners[slot];
    closeRun(P);
    out.insert(out.end(), P.zones.begin(), P.zones.end());
    S.slotOfFibre[P.fibre] = -1;
  }
  return tested;
}

void writeZones(const ZoneCache& cache, ZoneStore& z) {
  resizeColumns(z, cache.chunkFirst.back());
  const Index chunks = Index(cache.chunkZones.size());
  tbb::parallel_for(Index(0), chunks, [&](Index k) {
    Index at = cache.chunkFirst[k];
    for (const ZoneRecord& r : cache.chunkZones[k]) {
      z.fibreI[at] = r.fibreI;
      z.fibreJ[at] = r.fibreJ;
      z.sI1[at] = r.sI1;
      z.sI2[at] = r.sI2;
      z.sJ1[at] = r.sJ1;
      z.sJ2[at] = r.sJ2;
      z.minDistance[at] = r.minDistance;
      z.testPoints[at] = r.testPoints;
      z.id[at] = 0;
      z.previous[at] = -1;
      z.intermediateLength[at] = 0;
      z.firstElement[at] = z.elementCount[at] = 0;
      z.penalty[at] = z.pMax[at] = z.friction[at] = z.stiffness[at] = 0;
      z.penaltyMin[at] = z.penaltyMax[at] = 0;
      z.refined[at] = 0;
      ++at;
    }
  });
}

}  // namespace

void buildZones(const FibreStore& fs, const ContactParams& params,
                const CentrelineStore& centrelines, const BroadphaseCache& broadphase,
                ZoneCache& cache, ZoneStore& zones, Trace* trace, const Cancel& cancel) {
  Span span(trace, "contact-zones");
  const Index nF = fs.fibres();
  const Index chunks = (nF + kFibreChunk - 1) / kFibreChunk;
  cache.chunkZones.resize(chunks);
  std::vector<std::int64_t> tested(chunks);
  tbb::parallel_for(tbb::blocked_range<Index>(0, chunks, 1), [&](const tbb::blocked_range<Index>& r) {
    ZoneScratch& S = cache.scratch.local();
    if (Index(S.slotOfFibre.size()) != nF) S.slotOfFibre.assign(nF, -1);
    for (Index k = r.begin(); k != r.end(); ++k) {
      std::vector<ZoneRecord>& out = cache.chunkZones[k];
      out.clear();
      tested[k] = 0;
      if (cancel()) continue;
      for (Index I = k * kFibreChunk; I < std::min(nF, (k + 1) * kFibreChunk); ++I)
        tested[k] += buildFibre(fs, params, centrelines, broadphase, I, S, out);
    }
  });
  cache.chunkFirst.resize(chunks + 1);
  cache.chunkFirst[0] = 0;
  std::int64_t total = 0;
  for (Index k = 0; k < chunks; ++k) {
    cache.chunkFirst[k + 1] = cache.chunkFirst[k] + Index(cache.chunkZones[k].size());
    total += tested[k];
  }
  writeZones(cache, zones);
  span.items(total);
}

}  // namespace fibra
