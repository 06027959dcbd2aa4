// The intermediate geometry of a proximity zone (eq. 5) and where its contact elements sit on
// it (eqs. 6-7 and their replacements): the zone's linear map zeta -> (sI(zeta), sJ(zeta)), its
// length L_int, the cuts at the fibres' element ends and the Gauss, Lobatto or equally spaced
// abscissas with their lengths.
//
// Reads  FibreStore (lengths, element counts), CentrelineStore (the element polynomials),
//        ContactParams (element_placement, the pair's p_max).
// Writes nothing: pure functions of a zone, called per zone and detection by
//        systems/contact_elements.cpp.
#pragma once

#include "components/contact_cache.h"
#include "components/fibres.h"
#include "systems/contact_geometry.h"
#include "systems/contact_params.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

namespace fibra {

// The intermediate geometry of one zone (eq. 5): zeta -> sI(zeta), sJ(zeta).
struct Intermediate {
  const FibreStore& fs;
  const CentrelineStore& cl;
  Index I, J;
  double sI1, sI2, sJ1, sJ2;  // the zone's intervals, mm
  double dI, dJ;              // their signed lengths, mm

  // (1 - zeta) s1 + zeta s2: exactly s1 and s2 at the zone ends
  double sI(double zeta) const { return (1 - zeta) * sI1 + zeta * sI2; }
  double sJ(double zeta) const { return (1 - zeta) * sJ1 + zeta * sJ2; }
  // x_int(zeta), mm
  Vec3 position(double zeta) const {
    return 0.5 * (centrelineAt(fs, cl, I, sI(zeta)).x + centrelineAt(fs, cl, J, sJ(zeta)).x);
  }
  // dx_int / dzeta, mm
  Vec3 tangent(double zeta) const {
    return 0.5 * (centrelineTangent(fs, cl, I, sI(zeta)) * dI +
                  centrelineTangent(fs, cl, J, sJ(zeta)) * dJ);
  }
};

// Successive zeta in (0, 1) where s1 + zeta d crosses an element end n h.
struct Breakpoints {
  double s1, d, h;
  std::int64_t n;  // next element end index
  Breakpoints(double s1_, double d_, double h_) : s1(s1_), d(d_), h(h_) {
    n = d > 0 ? std::int64_t(std::floor(s1 / h)) + 1 : std::int64_t(std::ceil(s1 / h)) - 1;
  }
  double peek() const {
    if (d == 0) return 1;
    const double z = (double(n) * h - s1) / d;
    return z > 0 && z < 1 ? z : 1;
  }
  void advance() { n += d > 0 ? 1 : -1; }
};

// L_int = int_0^1 |t_int| dzeta, two-point Gauss per piece between element ends (mm).
double intermediateLength(const Intermediate& g);

// The zeta where the intermediate geometry crosses the plane through the element end x_f(s)
// normal to the mean tangent there: the root of F(zeta) = (x_int(zeta) - x_f(s)) . t_hat, with
// t_hat = t_int at `guess` (the zone's linear map of s) built from f's node tangent (the mean of
// its elements' one-sided tangents: F is continuous where t_int has a kink). The eq. 8 sections
// there are at s on f up to the kink. Within `window` of the guess (clamped to [0, 1]): the
// window scanned in 8 steps, the sign change nearest the guess refined by the Illinois method;
// the guess itself when F keeps its sign.
double sectionAbscissa(const Intermediate& g, Index f, double s, double guess, double window);

// The placement of zone z's line elements: Lobatto where the acceptance refined the zone
// (ZoneStore::refined), the scene's `element_placement` elsewhere.
inline ElementPlacement zonePlacement(const ContactParams& p, const ZoneStore& zones, Index z) {
  return zones.refined[z] ? ElementPlacement::Lobatto : p.placement;
}

// Lobatto sampling: the missed dip of the gap g(zeta) = |D| - R_I - R_J, D = x_I - x_J, between
// samples dz apart is at most K dz^2 / 8 for K >= |g''| on the piece. With K estimated below,
// it is kept within kSagShare p_max (the tools' rule, systems/tool_detection.h) by cutting the
// piece into m Simpson sub-pieces (samples (b - a) / 2m apart), m <= kMaxSimpsonParts. On a
// piece both sections lie in one element each, so with x = P.a + P.b z + P.c z^2 and
// dz/dzeta = 2 d / h:
//   D'' = 2 c_I (2 d_I / h_I)^2 - 2 c_J (2 d_J / h_J)^2   (constant on the piece),
//   g'' = n . D'' + |D'_perp|^2 / |D|, estimated by |D''| + the larger of |D'_perp|^2 / |D| at
// the piece's ends, |D| taken at least (R_I + R_J) / 2: an estimate, not a bound (|D| is least
// inside the piece, at a dip; a piece that spans a dropped sliver cut uses its midpoint's
// elements), and m is capped. So the Lobatto elements sample the gap much more finely than the
// Gauss points but do not guarantee p_max / 4. Bent fibres lying side by side (a yarn's) dip
// between samples by 1.1 p_max at h / 2 spacing (37 fibres, 8 elements, measured); a shallow
// crossing's closest point lies between them. m follows the state, so a zone's element count
// may change from one detection to the next.
constexpr double kSagShare = 0.25;
constexpr int kMaxSimpsonParts = 8;

int simpsonParts(const Intermediate& g, double a, double b, double sag);

// The contact elements of a zone: visit(zeta, length) in increasing zeta. floor(2 L_int / h_min)
// (eq. 6) decides between a point contact (< 2: one element at zeta = 1/2 carrying L_int) and a
// line contact. A line contact is cut where the eq. 8 sections cross the element ends of either
// fibre (sectionAbscissa, within one element's span of the zone's linear map; a cut within
// h_min / 10 of arc length of the previous one kept or of the zone's end is dropped, so no
// sliver piece remains). A piece's sections then lie within one element of I and one of J, and
// a uniform line pressure p gives both fibres the nodal forces of the consistent line load,
// int N_a p ds, exactly where the sections move affinely with zeta: the integrand is cubic in
// zeta and both rules below are exact for cubics. On a piece [a, b] of width w = b - a:
//   Gauss:   the two Gauss points (a + b) / 2 -+ w / (2 sqrt 3), each of length w / 2 |t_int|;
//   Lobatto: a, (a + b) / 2 and b with lengths w / 6, 4 w / 6, w / 6 times |t_int| (Simpson),
//            a cut shared by two pieces being one element carrying both sixths. Every kept
//            cut then carries an element: a kink of the centreline at a node, where the Gauss
//            points (0.21 h away) see the fibres apart, is sampled where it is deepest (a node
//            within h_min / 10 of a kept cut, whose cut was dropped, within that distance).
// Paper: eq. 7, Nc equally spaced elements zeta_k = (k - 1) / (Nc - 1), each of length L_int / Nc
// (equal weights).
// `placement`: the zone's (zonePlacement: the scene's `element_placement`, Lobatto for a zone
// the acceptance refined).
template <class Visit>
void forEachElementAbscissa(const Intermediate& g, double L, const ContactParams& p,
                           ElementPlacement placement, Visit visit) {
  const double hI = elementLength(g.fs, g.I), hJ = elementLength(g.fs, g.J);
  const double h = std::min(hI, hJ);
  const double count = std::floor(2 * L / h);
  if (count < 2) {
    visit(0.5, L);
    return;
  }
  if (placement == ElementPlacement::Paper) {
    for (int k = 0; k < int(count); ++k) visit(k / (count - 1), L / count);
    return;
  }
  std::vector<double> cuts;
  for (auto [f, s1, d, hf] : {std::tuple{g.I, g.sI1, g.dI, hI}, std::tuple{g.J, g.sJ1, g.dJ, hJ}})
    for (Breakpoints b(s1, d, hf); b.peek() < 1; b.advance())
      cuts.push_back(sectionAbscissa(g, f, double(b.n) * hf, b.peek(), hf / std::abs(d)));
  std::sort(cuts.begin(), cuts.end());
  const double sliver = 0.1 * h / std::max(std::abs(g.dI), std::abs(g.dJ));  // in zeta
  std::vector<double> ends{0.0};  // the pieces' ends: 0, the kept cuts, 1
  for (const double b : cuts)
    if (b - ends.back() >= sliver && 1 - b >= sliver) ends.push_back(b);
  ends.push_back(1.0);
  const std::size_t pieces = ends.size() - 1;
  if (placement == ElementPlacement::Weighted) {
    const double r = 0.5 / std::sqrt(3.0);
    for (std::size_t k = 0; k < pieces; ++k) {
      const double mid = 0.5 * (ends[k] + ends[k + 1]), w = ends[k + 1] - ends[k];
      for (const double z : {mid - r * w, mid + r * w}) visit(z, 0.5 * w * g.tangent(z).norm());
    }
    return;
  }
  // Composite Simpson on each piece, in simpsonParts sub-pieces; |t_int| at a sub-piece's ends
  // taken just inside it (t_int kinks at a node).
  const double sag = kSagShare * pairPMax(p, g.I, g.J);
  std::vector<double> sub{0.0};
  for (std::size_t k = 0; k < pieces; ++k) {
    const int m = simpsonParts(g, ends[k], ends[k + 1], sag);
    for (int i = 1; i <= m; ++i) sub.push_back(ends[k] + (ends[k + 1] - ends[k]) * i / m);
  }
  sub.back() = 1.0;
  const std::size_t n = sub.size() - 1;
  std::vector<double> atEnd(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double a = sub[k], b = sub[k + 1], inside = 1e-9 * (b - a);
    atEnd[k] += (b - a) / 6 * g.tangent(a + inside).norm();
    atEnd[k + 1] += (b - a) / 6 * g.tangent(b - inside).norm();
  }
  for (std::size_t k = 0; k <= n; ++k) {
    visit(sub[k], atEnd[k]);
    if (k == n) break;
    const double mid = 0.5 * (sub[k] + sub[k + 1]);
    visit(mid, 4 * (sub[k + 1] - sub[k]) / 6 * g.tangent(mid).norm());
  }
}

}  // namespace fibra
