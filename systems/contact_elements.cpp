#include "systems/contact_elements.h"

#include "core/columns.h"
#include "systems/contact_geometry.h"
#include "systems/contact_intermediate.h"
#include "systems/contact_normals.h"
#include "systems/contact_sections.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibra {
namespace {

// The interval of a zone on one fibre widened by Delta_prox and clamped to the fibre, mm.
std::pair<double, double> widened(const FibreStore& fs, Index f, double s1, double s2, double delta) {
  return {std::max(0.0, std::min(s1, s2) - delta), std::min(fs.length[f], std::max(s1, s2) + delta)};
}

Vec3 unitTangent(const Section& s) { return s.dx0ds.normalized(); }

// Particle direction when the other centre gives none: n = t_I x t_J, else I's director g1.
Vec3 fallbackDirection(const Section& I, const Section& J) {
  const Vec3 n = unitTangent(I).cross(unitTangent(J));
  return n.norm() > 1e-12 ? Vec3(n.normalized()) : Vec3(I.g1.normalized());
}

void particles(const Section& I, const Section& J, double RI, double RJ, double xiI[2],
               double xiJ[2], std::uint8_t& flags) {
  const Vec3 d = J.x0 - I.x0;
  const bool okI = outlinePoint(I.g1, I.g2, RI, d, xiI);
  const bool okJ = outlinePoint(J.g1, J.g2, RJ, -d, xiJ);
  if (okI && okJ) return;
  const Vec3 n = fallbackDirection(I, J);
  if (!okI) {
    flags |= kFallbackParticleI;
    if (!outlinePoint(I.g1, I.g2, RI, -n, xiI)) xiI[0] = -RI, xiI[1] = 0;
  }
  if (!okJ) {
    flags |= kFallbackParticleJ;
    if (!outlinePoint(J.g1, J.g2, RJ, n, xiJ)) xiJ[0] = RJ, xiJ[1] = 0;
  }
}

// The other side's particle against an end face at x: J's outline point towards x (kept as it
// was when x lies on J's axis).
void facingParticle(const Section& J, double RJ, const Vec3& x, double xi[2]) {
  outlinePoint(J.g1, J.g2, RJ, x - J.x0, xi);
}

struct ElementSides {
  double sI, sJ;
  std::uint8_t flags;
};

// Where a zone's sections are sought: its intervals on I and J widened by Delta_prox, clamped to
// the fibres (mm; one per zone, shared by its elements).
using Windows = SectionWindows;
Windows searchWindows(const Intermediate& g, double delta) {
  const auto [aI, bI] = widened(g.fs, g.I, g.sI1, g.sI2, delta);
  const auto [aJ, bJ] = widened(g.fs, g.J, g.sJ1, g.sJ2, delta);
  return {aI, bI, aJ, bJ};
}

double centreDistance(const Intermediate& g, double sI, double sJ) {
  return (centrelineAt(g.fs, g.cl, g.I, sI).x - centrelineAt(g.fs, g.cl, g.J, sJ).x).norm();
}

// The sections of I and J at zeta (eq. 8 and its degenerate cases) within the zone's windows;
// `sep` is the self-contact separation (I == J). Where eq. 8 is well posed on both fibres, the
// pair then moves to the nearest sections in its plane (systems/contact_sections.h) when that
// brings the centres closer by more than `gain` (mm, p_max / 10 at the call sites): fibres that
// face each other at their eq. 8 sections keep them bitwise.
ElementSides sectionsAt(const Intermediate& g, double zeta, const Windows& w, double sep,
                        double gain) {
  const FibreStore& fs = g.fs;
  const double sIz = g.sI(zeta), sJz = g.sJ(zeta);
  CentrelinePoint cI = centrelineAt(fs, g.cl, g.I, sIz), cJ = centrelineAt(fs, g.cl, g.J, sJz);
  cI.dxds = centrelineTangent(fs, g.cl, g.I, sIz);
  cJ.dxds = centrelineTangent(fs, g.cl, g.J, sJz);
  const Vec3 xInt = 0.5 * (cI.x + cJ.x);
  const Vec3 tInt = 0.5 * (cI.dxds * g.dI + cJ.dxds * g.dJ);
  ElementSides out{sIz, sJz, 0};
  Vec3 t;
  if (tInt.norm() > 1e-9 * 0.5 * (std::abs(g.dI) + std::abs(g.dJ))) {
    t = tInt.normalized();
  } else {
    const Vec3 tI = cI.dxds.normalized(), tJ = cJ.dxds.normalized();
    t = (tI + (tI.dot(tJ) < 0 ? -tJ : tJ)).normalized();
    out.flags |= kFallbackTangent;
  }
  double aI = w.aI, bI = w.bI, aJ = w.aJ, bJ = w.bJ;  // narrowed below for self-contact
  const bool okI = planeCut(fs, g.cl, g.I, xInt, t, sIz, cI, aI, bI, out.sI);
  const bool okJ = planeCut(fs, g.cl, g.J, xInt, t, sJz, cJ, aJ, bJ, out.sJ);
  if (okI && okJ) {
    double sI = out.sI, sJ = out.sJ;
    if (nearestSectionsInPlane(fs, g.cl, g.I, g.J, xInt, t, w, sep, sI, sJ) &&
        centreDistance(g, sI, sJ) < centreDistance(g, out.sI, out.sJ) - gain)
      out.sI = sI, out.sJ = sJ;
    return out;
  }
  if (!okI) out.flags |= kFallbackSectionI;
  if (!okJ) out.flags |= kFallbackSectionJ;
  if (!okI && okJ) {  // self-contact: I stays the separation below J
    if (g.I == g.J) bI = std::min(bI, out.sJ - sep);
    if (aI <= bI) out.sI = closestOnFibre(fs, g.cl, g.I, centrelineAt(fs, g.cl, g.J, out.sJ).x, aI, bI).s;
  } else {
    if (g.I == g.J) aJ = std::max(aJ, out.sI + sep);
    if (aJ <= bJ) out.sJ = closestOnFibre(fs, g.cl, g.J, centrelineAt(fs, g.cl, g.I, out.sI).x, aJ, bJ).s;
  }
  return out;
}

// A point element's sections moved to the closest sections near them (systems/contact_sections.h).
bool closestSections(const Intermediate& g, const Windows& w, double thetaParallel, double sep,
                     ElementSides& sides, double* curvature = nullptr) {
  return closestSectionsNear(g.fs, g.cl, g.I, g.J, w, thetaParallel, sep, sides.sI, sides.sJ,
                             curvature);
}

// The zeta of a pair of sections along the zone: of sI on I's interval, or of sJ where J's
// interval is the longer (not finite on a zone of zero length).
double zetaAlong(const Intermediate& g, const ElementSides& s) {
  return std::abs(g.dI) >= std::abs(g.dJ) ? (s.sI - g.sI1) / g.dI : (s.sJ - g.sJ1) / g.dJ;
}

// The element of a zone that goes to the closest points: among those not `taken`, the one whose
// zeta is nearest theirs (zetaAlong); -1 when all are taken.
Index nearestElement(const Intermediate& g, const ContactElementStore& el, Index first, Index nc,
                     const ElementSides& closest, const std::vector<char>& taken) {
  const double zeta = zetaAlong(g, closest);
  Index best = -1;
  for (Index e = first; e < first + nc; ++e)
    if (!taken[e - first] && (best < 0 || std::abs(el.zeta[e] - zeta) < std::abs(el.zeta[best] - zeta)))
      best = e;
  return best;
}

// The particles of eq. 9 (towards the other section's centre), or on an end face when one
// section is an end of its fibre and the other lies beyond it: the face point deepest in the
// other fibre, whose section moves to that point's closest centreline point (endFaceContact).
void particlesWithEndFaces(const FibreStore& fs, const Eigen::VectorXd& q, const Intermediate& g,
                           double sep, ElementSides& sides, Section& I, Section& J,
                           double xiI[2], double xiJ[2], std::uint8_t& flags) {
  particles(I, J, fs.radius[g.I], fs.radius[g.J], xiI, xiJ, flags);
  double xiE[2];
  const double clearI = kFaceClearance * fs.radius[g.I], clearJ = kFaceClearance * fs.radius[g.J];
  if (endFaceContact(fs, q, g.cl, g.I, sides.sI, I, g.J, sep, clearJ, sides.sJ, J, xiE)) {
    xiI[0] = xiE[0], xiI[1] = xiE[1];
    facingParticle(J, fs.radius[g.J], I.x0 + xiE[0] * I.g1 + xiE[1] * I.g2, xiJ);
    flags |= kEndFaceI;
  } else if (endFaceContact(fs, q, g.cl, g.J, sides.sJ, J, g.I, sep, clearI, sides.sI, I, xiE)) {
    xiJ[0] = xiE[0], xiJ[1] = xiE[1];
    facingParticle(I, fs.radius[g.I], J.x0 + xiE[0] * J.g1 + xiE[1] * J.g2, xiI);
    flags |= kEndFaceJ;
  }
}

// Under a forced normal N (from J to I): I's particle on its outline towards -N, J's towards +N,
// whatever the centres do (they may coincide where the centrelines cross). A section whose plane
// N is normal to keeps the particle of eq. 9 (with its fallback).
void forcedParticles(const Section& I, const Section& J, double RI, double RJ, const Vec3& N,
                     double xiI[2], double xiJ[2], std::uint8_t& flags) {
  const bool okI = outlinePoint(I.g1, I.g2, RI, -N, xiI);
  const bool okJ = outlinePoint(J.g1, J.g2, RJ, N, xiJ);
  if (okI && okJ) return;
  double eqI[2], eqJ[2];
  particles(I, J, RI, RJ, eqI, eqJ, flags);
  if (!okI) xiI[0] = eqI[0], xiI[1] = eqI[1];
  if (!okJ) xiJ[0] = eqJ[0], xiJ[1] = eqJ[1];
}

// The minima of the centreline distance within a zone, where its elements go.
// Where two fibres (or two strands of one) cross, the gap has an isolated minimum; near it the
// centreline distance grows as d = d0 + delta^T H delta / (2 d0) (H = dF of closestSections,
// delta the offsets in sI and sJ), so a penetration p_max reaches out to |delta| = l with
//   l = sqrt(2 (R_I + R_J) p_max / lambda_min(H)).
// Long zones: where 2 l is below the elements' spacing h_min / 2, they sample the patch once at
// most, at sections up to h_min / 4 off the closest ones, and their gaps miss the overlap there
// (a flat 2 x 2 plain weave of 40-element fibres: 22 p_max of overlap where they reported 5.8,
// docs/CONTACT.md "Crossings in long zones"): each such narrow minimum takes the nearest
// element (the others stay, and still catch the fibres where they slide).
// Point zones (one element): a strand bent round the other (a tight loop crossing itself, a
// fibre wrapped over a crossing) comes closest to it at two or more places a few hundredths of a
// mm apart. One element at one of them lets the solve push the strands apart there and through
// each other at the other, and the next detection's element jumps there (the plectoneme's loop
// at t = 0.735: 12 p_max at one, 4.6 at the other, by turns, until the increment failed). Every
// minimum whose centres lie within R_I + R_J + 2 p_max (that touches, or nearly) then carries an
// element of its own, L_int / m each for m such minima (one: the zone's element goes to it).
// Sought once per detection, in the counting pass (zoneElementCount), for point zones; per long
// zone in its element pass.
// The minima: closestSections from the eq. 8 sections at zeta = 1/2 (first), then from the
// zone's linear map (sI(zeta_k), sJ(zeta_k)), zeta_k = k / n, n = ceil(8 L_int / h_min) within
// [4, 256] (point zones: every k; long zones, for their cost: the k where the fibres make more
// than theta_parallel, as closestSections keeps no minimum elsewhere); distinct
// (|dsI| + |dsJ| > h_min / 20); ordered along the zone. Fibre ends bound the search (an end-held
// minimum: the closest approach lies past an end); in a long zone one is kept where the fibres
// make more than theta_cross there (a crossing over an end), not narrowness (which a held
// section does not measure), nor below (converging line contacts end there).
enum class Minima { Narrow, Touching };

// Whether a pair of sections lies at an end of either fibre (a minimum held there).
bool atEnd(const Intermediate& g, const ElementSides& s) {
  return s.sI <= 0 || s.sI >= g.fs.length[g.I] || s.sJ <= 0 || s.sJ >= g.fs.length[g.J];
}

// |t_I x t_J| at a pair of sections: the sine of the fibres' angle there.
double crossingAt(const Intermediate& g, const ElementSides& s) {
  const Vec3 tI = centrelineAt(g.fs, g.cl, g.I, s.sI).dxds.normalized();
  const Vec3 tJ = centrelineAt(g.fs, g.cl, g.J, s.sJ).dxds.normalized();
  return tI.cross(tJ).norm();
}

// Kinked vertices (kinkedNode, systems/contact_geometry.h) in the windows that point at the
// other fibre: the centre distance to the other fibre's closest point (closestPointOnFibre)
// rises along both elements that meet there, d . t_after >= 0 >= d . t_before (d from the other
// fibre's point to the vertex). Such a vertex is a narrow minimum that closestSections, Newton on
// smooth pieces, never lands on: between two elements' sections a V-shaped fibre pressed by its
// vertex onto a straight one overlapped it by 1.5 p_max where the elements reported 0.49, and
// every attempt failed as an inconsistent set. Appended to `minima` unless already there.
void kinkMinima(const Intermediate& g, const Windows& w, const ContactParams& p, double sep,
                double h, std::vector<ElementSides>& minima) {
  for (const bool onI : {true, false}) {
    const Index f = onI ? g.I : g.J, o = onI ? g.J : g.I;
    const double hf = elementLength(g.fs, f), lo = onI ? w.aI : w.aJ, hi = onI ? w.bI : w.bJ;
    const Index first = g.fs.firstElement[f], n = g.fs.elementCount[f];
    for (Index k = std::max<Index>(1, Index(std::ceil(lo / hf))); k < n && k * hf <= hi; ++k) {
      if (!kinkedNode(g.fs, g.cl, f, k, p.thetaParallel)) continue;
      const double sk = k * hf;
      const CentrelinePolynomial &A = g.cl.poly[first + k - 1], &B = g.cl.poly[first + k];
      const Vec3 x = B.a - B.b + B.c;  // the node: x0(z = -1) of the element after it
      double so = onI ? 0.5 * (w.aJ + w.bJ) : 0.5 * (w.aI + w.bI);
      closestPointOnFibre(g.fs, g.cl, o, x, onI ? w.aJ : w.aI, onI ? w.bJ : w.bI, so);
      const Vec3 d = x - centrelineAt(g.fs, g.cl, o, so).x;
      if (!(d.dot(B.b - 2 * B.c) >= 0 && d.dot(A.b + 2 * A.c) <= 0)) continue;
      const ElementSides sides = onI ? ElementSides{sk, so, 0} : ElementSides{so, sk, 0};
      if (g.I == g.J && !(std::abs(sides.sJ - sides.sI) >= sep)) continue;
      const bool known = std::any_of(minima.begin(), minima.end(), [&](const ElementSides& m) {
        return std::abs(m.sI - sides.sI) + std::abs(m.sJ - sides.sJ) <= h / 20;
      });
      if (!known) minima.push_back(sides);
    }
  }
}

std::vector<ElementSides> zoneMinima(const Intermediate& g, const Windows& w,
                                     const ContactParams& p, double sep, double L, Minima kind) {
  const double h = std::min(elementLength(g.fs, g.I), elementLength(g.fs, g.J));
  const double pMax = pairPMax(p, g.I, g.J), RR = g.fs.radius[g.I] + g.fs.radius[g.J];
  const bool point = kind == Minima::Touching;
  const int n = int(std::clamp(std::ceil(8 * L / h), 4.0, 256.0));
  const double sinParallel = std::sin(p.thetaParallel);
  std::vector<ElementSides> starts{sectionsAt(g, 0.5, w, sep, 0.1 * pMax)};
  for (int k = 0; k <= n; ++k) {
    const double zeta = double(k) / n;
    const ElementSides start{g.sI(zeta), g.sJ(zeta), 0};
    if (point || crossingAt(g, start) > sinParallel) starts.push_back(start);
  }
  const double sinCross = std::sin(p.thetaCross);
  std::vector<ElementSides> minima;
  for (ElementSides sides : starts) {
    double lambda = 0;
    if (!closestSections(g, w, p.thetaParallel, sep, sides, &lambda)) continue;
    const bool keep = kind == Minima::Narrow
                          ? atEnd(g, sides) ? crossingAt(g, sides) > sinCross
                                            : lambda > 0 && 2 * std::sqrt(2 * RR * pMax / lambda) < 0.5 * h
                          : centreDistance(g, sides.sI, sides.sJ) < RR + 2 * pMax;
    const bool known = std::any_of(minima.begin(), minima.end(), [&](const ElementSides& m) {
      return std::abs(m.sI - sides.sI) + std::abs(m.sJ - sides.sJ) <= h / 20;
    });
    if (keep && !known) minima.push_back(sides);
  }
  if (kind == Minima::Narrow) kinkMinima(g, w, p, sep, h, minima);
  // Along the zone (zetaAlong); a zone of zero length by (sI, sJ).
  const bool flat = g.dI == 0 && g.dJ == 0;
  std::stable_sort(minima.begin(), minima.end(), [&](const ElementSides& a, const ElementSides& b) {
    if (flat) return a.sI < b.sI || (a.sI == b.sI && a.sJ < b.sJ);
    return zetaAlong(g, a) < zetaAlong(g, b);
  });
  return minima;
}

// A section at an interior node of its fibre lies in either element there; locate() takes the
// one after. The Lobatto placement puts elements at nodes, and where the other fibre's node lies
// within a sliver of it the two neighbouring pieces pair (i - 1, m - 1) and (i, m): taking the
// node's element i against m - 1 would couple a pair of beam elements that nothing else
// couples, a new clique whose fill doubled the factorisation (37-fibre yarn, measured). So a
// section within kAtNode h of an interior node is moved to the node, kInside h into the element
// that its neighbour in zeta uses on the side where the other fibre's element is the same. The
// cuts' sections land up to 2e-5 h off their nodes (eq. 8's plane is normal to t_int, the cut's
// to the mean tangent): a move of at most 1e-3 h along the fibre. kInside is beyond the node
// rule's 1e-9 h (kNodeSnap, systems/contact_geometry.h) by a margin no rounding of s / h
// crosses: the section is a point of that element alone (its one-sided tangent, and no widened
// clique when the normals are linearised in Newton).
constexpr double kAtNode = 1e-3, kInside = 1e-7;

void pairElementsAtNodes(const Intermediate& g, std::vector<ElementSides>& all) {
  const std::size_t n = all.size();
  for (const bool onI : {true, false}) {
    const Index f = onI ? g.I : g.J, o = onI ? g.J : g.I;
    const double h = elementLength(g.fs, f);
    const Index count = g.fs.elementCount[f];
    auto sf = [&](std::size_t k) -> double& { return onI ? all[k].sI : all[k].sJ; };
    auto so = [&](std::size_t k) { return onI ? all[k].sJ : all[k].sI; };
    for (std::size_t k = 0; k < n; ++k) {
      const double node = std::round(sf(k) / h);
      if (node <= 0 || node >= double(count) || std::abs(sf(k) - node * h) > kAtNode * h) continue;
      const Index other = locate(g.fs, o, so(k)).element;
      const bool before = k > 0 && locate(g.fs, o, so(k - 1)).element == other;
      const std::size_t neighbour = before ? k - 1 : std::min(k + 1, n - 1);
      if (neighbour == k) continue;
      const Index element = locate(g.fs, f, sf(neighbour)).element - g.fs.firstElement[f];
      if (element == Index(node) - 1) sf(k) = (node - kInside) * h;
      else if (element == Index(node)) sf(k) = (node + kInside) * h;
    }
  }
}

// Whether a pair of sections has one at a kinked interior node of its fibre, or within kAtNode h
// of it (pairElementsAtNodes above moves a section at a node kInside h into an element).
bool atKink(const Intermediate& g, const ElementSides& s, double angle) {
  const auto kinked = [&](Index f, double sf) {
    const double h = elementLength(g.fs, f), node = std::round(sf / h);
    return node > 0 && node < double(g.fs.elementCount[f]) &&
           std::abs(sf - node * h) <= kAtNode * h && kinkedNode(g.fs, g.cl, f, Index(node), angle);
  };
  return kinked(g.I, s.sI) || kinked(g.J, s.sJ);
}

// The zone's element count: the abscissas of forEachElementAbscissa, or a point zone's dips (its
// touching minima, zoneMinima) when it has any; `dips` receives them (empty otherwise).
Index zoneElementCount(const Intermediate& g, double L, const ContactParams& p,
                       ElementPlacement placement, std::vector<ElementSides>& dips) {
  Index count = 0;
  forEachElementAbscissa(g, L, p, placement, [&](double, double) { ++count; });
  dips.clear();
  if (count != 1) return count;
  const double sep = g.I == g.J ? p.selfSeparation[g.I] : 0;
  dips = zoneMinima(g, searchWindows(g, proximityDistance(p, g.I, g.J)), p, sep, L,
                    Minima::Touching);
  return dips.empty() ? 1 : Index(dips.size());
}

// `dips`: the point zone's touching minima from zoneElementCount (nc of them, or none).
void zoneElements(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                  const Intermediate& g, const ZoneStore& zones, Index z,
                  const std::vector<ElementSides>& dips, ContactElementStore& el) {
  const Index nc = zones.elementCount[z], first = zones.firstElement[z];
  const Windows windows = searchWindows(g, proximityDistance(p, g.I, g.J));
  const double sep = g.I == g.J ? p.selfSeparation[g.I] : 0;
  const double gain = 0.1 * pairPMax(p, g.I, g.J);
  const double L = zones.intermediateLength[z];
  const ElementPlacement placement = zonePlacement(p, zones, z);
  double total = 0;
  Index e = first;
  forEachElementAbscissa(g, L, p, placement, [&](double zeta, double length) {
    el.zeta[e] = zeta;
    el.length[e++] = length;
    total += length;
  });
  // A point zone's dips: an element at each, L_int / nc each; one dip keeps the abscissa's
  // zeta = 1/2 and L_int.
  for (std::size_t k = 0; nc > 1 && k < dips.size(); ++k) {
    const double zeta = zetaAlong(g, dips[k]);
    el.zeta[first + Index(k)] = std::isfinite(zeta) ? zeta : 0.5;
    el.length[first + Index(k)] = L / double(nc);
  }
  for (e = first; e < first + nc; ++e)
    el.weight[e] = total > 0 ? el.length[e] * double(nc) / total : 1.0;
  // A long zone's narrow minima (crossings) each to its nearest element.
  std::vector<char> atCrossing(nc, !dips.empty());
  std::vector<ElementSides> all(nc);
  if (nc > 1 && dips.empty())
    for (const ElementSides& c : zoneMinima(g, windows, p, sep, L, Minima::Narrow)) {
      const Index k = nearestElement(g, el, first, nc, c, atCrossing);
      if (k < 0) break;
      all[k - first] = c, atCrossing[k - first] = 1;
    }
  for (e = first; e < first + nc; ++e)
    if (!dips.empty()) all[e - first] = dips[e - first];
    else if (!atCrossing[e - first]) all[e - first] = sectionsAt(g, el.zeta[e], windows, sep, gain);
  if (nc > 1 && dips.empty() && placement == ElementPlacement::Lobatto) pairElementsAtNodes(g, all);
  for (e = first; e < first + nc; ++e) {
    ElementSides sides = all[e - first];
    // a kinked vertex is not a crossing to follow: loop B's closest points (crossing_follow)
    // are those of smooth pieces
    const bool closest =
        (atCrossing[e - first] && !atKink(g, sides, p.thetaParallel)) ||
        (nc == 1 && closestSections(g, windows, p.thetaParallel, sep, sides));
    Section I = contactSection(fs, q, g.I, sides.sI);
    Section J = contactSection(fs, q, g.J, sides.sJ);
    double xiI[2], xiJ[2];
    std::uint8_t flags = sides.flags;
    const int forced = g.I == g.J ? 0 : forcedSign(p, g.I, sides.sI, g.J, sides.sJ);
    const Vec3 N = forced * p.forcedNormal;
    if (forced)
      forcedParticles(I, J, fs.radius[g.I], fs.radius[g.J], N, xiI, xiJ, flags);
    else
      particlesWithEndFaces(fs, q, g, sep, sides, I, J, xiI, xiJ, flags);
    el.zone[e] = z;
    el.fibreI[e] = g.I;
    el.sI[e] = sides.sI;
    el.xiI1[e] = xiI[0];
    el.xiI2[e] = xiI[1];
    el.fibreJ[e] = g.J;
    el.sJ[e] = sides.sJ;
    el.xiJ1[e] = xiJ[0];
    el.xiJ2[e] = xiJ[1];
    const NormalGap ng =
        forced ? forcedNormalAndGap(I, J, xiI, xiJ, N, p.forcedAllowance)
               : normalAndGap(I, J, xiI, xiJ, fs.radius[g.I], fs.radius[g.J], p.thetaParallel,
                              p.thetaCross, flags,
                              endRoom(fs, q, g.I, sides.sI, g.J, sides.sJ, p.thetaParallel));
    el.normal[e] = ng.normal;
    el.gap[e] = ng.gap;
    el.theta[e] = ng.theta;
    el.crossWeight[e] = ng.crossWeight;
    el.fallback[e] = flags | (ng.fallback ? kFallbackNormal : 0);
    el.forced[e] = std::int8_t(forced);
    el.crossing[e] = closest && !forced && !(flags & (kEndFaceI | kEndFaceJ));
  }
}

}  // namespace

void generateContactElements(const FibreStore& fs, const Eigen::VectorXd& q,
                             const ContactParams& params, const CentrelineStore& centrelines,
                             ZoneStore& zones, ContactElementStore& elements, Trace* trace,
                             const Cancel& cancel) {
  Span span(trace, "contact-elements");
  const Index nz = zones.size();
  std::vector<std::vector<ElementSides>> dips(std::size_t(nz), std::vector<ElementSides>{});
  auto geometry = [&](Index z) {
    return Intermediate{fs, centrelines, zones.fibreI[z], zones.fibreJ[z], zones.sI1[z],
                        zones.sI2[z], zones.sJ1[z], zones.sJ2[z], zones.sI2[z] - zones.sI1[z],
                        zones.sJ2[z] - zones.sJ1[z]};
  };
  tbb::parallel_for(tbb::blocked_range<Index>(0, nz, 16), [&](const tbb::blocked_range<Index>& r) {
    for (Index z = r.begin(); z != r.end(); ++z) {
      const Intermediate g = geometry(z);
      const double L = intermediateLength(g);
      zones.intermediateLength[z] = L;
      zones.elementCount[z] =
          zoneElementCount(g, L, params, zonePlacement(params, zones, z), dips[std::size_t(z)]);
    }
  });
  Index total = 0;
  for (Index z = 0; z < nz; ++z) {
    zones.firstElement[z] = total;
    total += zones.elementCount[z];
  }
  resizeColumns(elements, total);
  tbb::parallel_for(tbb::blocked_range<Index>(0, nz, 4), [&](const tbb::blocked_range<Index>& r) {
    if (cancel()) return;
    for (Index z = r.begin(); z != r.end(); ++z)
      zoneElements(fs, q, params, geometry(z), zones, z, dips[std::size_t(z)], elements);
  });
  span.items(total);
}

}  // namespace fibra
