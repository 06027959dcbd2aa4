// Normals and gaps of the contact elements (eqs. 10, 11), for fixed particles. Run by the
// detection after the element generator, and again on its own whenever the normals are updated
// at a new state with the same contact elements (the paper's loop B).
//
// Reads  FibreStore, the state q, ContactParams (theta_cross, theta_parallel), the particles of
//        ContactElementStore.
// Writes ContactElementStore::normal, gap, theta, crossWeight, the kFallbackNormal bit and (the
//        update on its own) gRev0 and ContactLoopStats::normalTurn (over the elements whose
//        normal is fixed in a Newton pass: with normal_update "newton" the others already are
//        those of the state, systems/normal_linearisation.h).
// Threading: parallel over contact elements, each writing its own entries.
//
// With the sections of the two particles (centres x0, unit tangents t) and
//   theta = atan2(|t_I x t_J|, |t_I . t_J|) in [0, pi/2],
//   n_cross = t_I x t_J / |t_I x t_J|,  n_par = d / |d|,  d = P_t (x0I - x0J),
//   P_t = I - t t^T, t = the mean tangent (t_I + sign(t_I . t_J) t_J) / |...|,
//   w = clamp((theta - theta_par) / (theta_cross - theta_par), 0, 1)  (a step when they are equal),
//   N = normalised(w n_cross + (1 - w) n_par),  n_cross first turned so that n_cross.(x0I - x0J) >= 0,
// so that N points from J to I (N.d >= 0); the gap is gN = (xI(xi_I) - xJ(xi_J)).N.
// P_t removes the axial offset of the two sections: paired sections of parallel fibres drift
// apart along the axis as the fibres slide (by the slip of a pass), and the full centre-to-centre
// direction would tilt N by atan(offset / (R_I + R_J)), turning normal force into axial force
// (a spurious negative axial stiffness ~ sum R_N / (R_I + R_J), and a friction drag short by
// R_N tan(tilt)). On exact pairs (closest sections) the offset is zero and nothing changes.
// Swapping I and J flips N and keeps gN (n_cross and n_par are both odd in the swap).
// Crossings past an end: n_cross is the common normal of the two tangent lines, at their closest
// points x0I + lambda t_I and x0J + mu t_J,
//   lambda = (b dJ - dI) / (1 - b^2),  mu = (dJ - b dI) / (1 - b^2),  b = t_I.t_J,
//   dI = t_I.(x0I - x0J),  dJ = t_J.(x0I - x0J)  (mm along the lines from the sections).
// Where lambda or mu lies past a fibre's end within reach (beyond the arc length EndRoom gives
// it on that side), the fibres do not cross there: the gap along n_cross would be that of a fibre running on
// where it has ended. n_cross is then the unit vector between the closest points of the two
// segments the fibres cover (lambda in [-I0, I1], mu in [-J0, J1]): the nearest of the four
// pairs with one point held at an end of its segment and the other the best for it; where the
// lines' closest points lie within both fibres it is the common normal itself, so N turns
// continuously as they pass an end. (With the lines' normal, side elements near a tilted end
// read 0.2 mm of overlap, 2R, where the end stood 0.005 mm clear and the lines met, and held a
// pushed end 0.0135 mm clear of a fibre on 22 mN.) The end itself is the end face's element
// (systems/contact_elements.cpp).
// Sections on one axis (|d| <= 1e-9 (R_I + R_J) while the centres are apart: fibres meeting end
// to end) keep d = x0I - x0J.
// Degenerate: n_par undefined (|d| <= 1e-9 (R_I + R_J)) with w < 1: N = n_cross when
// w > 0; else (coincident centres of parallel fibres) N = (xJ - xI) / |xJ - xI| from the
// particles, which then face each other: a full penetration gN = -|xI - xJ|. kFallbackNormal.
//
// Forced normals (paper section 5.2.1; StepDef::forcedNormal): during a step that forces them,
// an element between fibres of different contact classes whose levels differ there has
//   N = sign D,  sign = +1 when I's level is the higher (I over J), else -1
// (systems/contact_params.h, forcedSign), whatever the centrelines do: they may cross (d = 0,
// eq. 10 undefined) or I may still lie below J. Its particles were put on the outlines facing
// along N at generation (I's towards -N, J's towards +N, systems/contact_elements.cpp), so that
// for circular sections gN = (x0I - x0J).N - (R_I + R_J) + a: negative until I has passed over J
// (a the overlap the step still allows, ContactParams::forcedAllowance; 0 without).
// N is constant, so the law's linearisation (fixed N, systems/contact_law.h) is exact.
#pragma once

#include "components/contact.h"
#include "components/iteration.h"
#include "core/trace.h"
#include "systems/contact_geometry.h"
#include "systems/contact_params.h"
#include "systems/interpolation.h"

#include <Eigen/Geometry>

#include <cmath>
#include <type_traits>

namespace fibra {

// The reference arc length of each fibre on either side of an element's sections (mm): I0 = sI,
// I1 = L_I - sI, J0 = sJ, J1 = L_J - sJ, each within kEndReach (R_I + R_J) of the section;
// infinite (no end to pass) beyond: the tangent lines stand for the fibres only near their
// sections (with every end, a plectoneme's ply 0.05 mm from its clamped end took the closest
// points of segments reaching 6.8 mm along a tangent line, 50 p_max of overlap where none was).
// A kink ends the room as an end does: a node within reach where the current tangents of the two
// elements that meet there differ by more than `kinkAngle` (rad; the callers pass theta_parallel),
// the room then running from the section to that node. Past a kink the tangent line no longer
// stands for the fibre: a V-shaped fibre resting on a straight one by its vertex had the common
// normal of one arm's tangent line and the straight fibre's axis, which meet in their plane far
// from the vertex (N 33 degrees off the plane, 0.15 p_max of penetration reported and 9 mN
// pushing where the fibres stood 28 p_max apart; tests/test_kinked_fibres.cpp).
constexpr double kEndReach = 2;

struct EndRoom {
  double I0 = HUGE_VAL, I1 = HUGE_VAL, J0 = HUGE_VAL, J1 = HUGE_VAL;
};

// Visits the kinks of fibre f's current centreline (q) at the interior nodes with reference arc
// length in [lo, hi] (mm): visit(k, s_k), k the node's element end (1 .. n - 1), s_k = k h.
template <class Visit>
void forEachKink(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double lo, double hi,
                 double kinkAngle, Visit&& visit) {
  const double h = elementLength(fs, f);
  const Index first = fs.firstElement[f], n = fs.elementCount[f];
  const Index kLo = std::max<Index>(1, Index(std::ceil(lo / h)));
  const Index kHi = std::min<Index>(n - 1, Index(std::floor(hi / h)));
  for (Index k = kLo; k <= kHi; ++k) {
    const Vec3 a = sectionAt(fs, q, {first + k - 1, 1.0}).dx0ds;
    const Vec3 b = sectionAt(fs, q, {first + k, -1.0}).dx0ds;
    if (std::atan2(a.cross(b).norm(), a.dot(b)) > kinkAngle) visit(k, k * h);
  }
}

// The arc length (mm) from the section at s of fibre f to the nearest kink before it (`before`)
// and after it (`after`) within `reach` of s, kinks as above; unchanged where there is none. A
// kink at the node where the section's own element starts lies before it; a section at a kinked
// node itself (interiorNodeAt: its tangent the mean of the two, contactSection) has no room on
// either side, so that n_cross runs from the vertex to the other fibre's segment.
inline void kinkRoom(const FibreStore& fs, const Eigen::VectorXd& q, Index f, double s,
                     double reach, double kinkAngle, double& before, double& after) {
  const Index own = locate(fs, f, s).element - fs.firstElement[f];  // the section's element
  const Index atNode = interiorNodeAt(fs, f, s);
  forEachKink(fs, q, f, s - reach, s + reach, kinkAngle, [&](Index k, double sk) {
    if (k == atNode) before = after = 0;
    else if (k <= own) before = std::min(before, std::max(0.0, s - sk));
    else after = std::min(after, std::max(0.0, sk - s));
  });
}

inline EndRoom endRoom(const FibreStore& fs, const Eigen::VectorXd& q, Index fI, double sI,
                       Index fJ, double sJ, double kinkAngle) {
  const double reach = kEndReach * (fs.radius[fI] + fs.radius[fJ]);
  const auto near = [reach](double room) { return room <= reach ? room : HUGE_VAL; };
  EndRoom r{near(sI), near(fs.length[fI] - sI), near(sJ), near(fs.length[fJ] - sJ)};
  kinkRoom(fs, q, fI, sI, reach, kinkAngle, r.I0, r.I1);
  kinkRoom(fs, q, fJ, sJ, reach, kinkAngle, r.J0, r.J1);
  return r;
}

struct NormalGap {
  Vec3 normal;
  double gap, theta, crossWeight;
  bool fallback;
};

template <class T>
using Vec3Of = Eigen::Matrix<T, 3, 1>;

// The value of a scalar or of a forward-mode derivative scalar (systems/normal_linearisation.h).
template <class T>
double valueOf(const T& x) {
  if constexpr (std::is_arithmetic_v<T>) return x;
  else return x.value();
}

template <class T>
struct NormalOf {
  Vec3Of<T> normal;
  double theta, crossWeight;
  bool fallback;
};

// Eqs. 10-11 (the rules above) on the section centres cI, cJ (mm), the centreline derivatives
// aI, aJ (dx0/ds, unit-free, not normalised) and the particles xI, xJ (mm); g1I: I's g1, the
// last resort of a fallback. Templated on the scalar so that systems/normal_linearisation.h
// differentiates this very code (T = double for the values, a forward-mode derivative scalar for
// dN/d(xI, xJ, cI, cJ, aI, aJ)): every branch is taken on the values, as for doubles.
template <class T>
NormalOf<T> normalOfSections(const Vec3Of<T>& cI, const Vec3Of<T>& cJ, const Vec3Of<T>& aI,
                             const Vec3Of<T>& aJ, const Vec3Of<T>& xI, const Vec3Of<T>& xJ,
                             const Vec3& g1I, double RI, double RJ, double thetaParallel,
                             double thetaCross, std::uint8_t flags, const EndRoom& room) {
  using std::abs;
  using std::atan2;
  using V = Vec3Of<T>;
  const V tI = aI.normalized(), tJ = aJ.normalized();
  V cross = tI.cross(tJ);
  const T theta = atan2(cross.norm(), abs(tI.dot(tJ)));
  if (flags & (kEndFaceI | kEndFaceJ)) {
    // An end face against the other fibre's side: N normal to that fibre's axis, through the
    // face particle (from J to I).
    const bool onI = flags & kEndFaceI;
    const V t = onI ? tJ : tI;
    const V r = onI ? V(xI - cJ) : V(cI - xJ);
    const V n = r - r.dot(t) * t;
    if (n.norm() > 1e-12 * (RI + RJ)) return {n.normalized(), valueOf(theta), 0, false};
  }
  // Centre-to-centre vector without its component along the mean tangent: the sections of a
  // pair drift apart along parallel fibres as they slide, and that axial offset must not tilt
  // the normal (a tilted normal turns normal force into axial force, docs/CONTACT.md).
  // Sections on one axis (fibres meeting end to end) keep the axial direction.
  const V t = (tI + (tI.dot(tJ) < 0 ? V(-tJ) : tJ)).normalized();
  const V centres = cI - cJ;
  V d = centres - centres.dot(t) * t;
  if (d.norm() <= 1e-9 * (RI + RJ)) d = centres;
  T w = T(theta > thetaCross ? 1.0 : 0.0);
  if (thetaCross > thetaParallel) {
    w = (theta - thetaParallel) / (thetaCross - thetaParallel);
    if (w < 0) w = T(0.0);
    if (w > 1) w = T(1.0);
  }
  if (w > 0) {
    cross.normalize();
    if (cross.dot(d) < 0) cross = -cross;
    // The tangent lines' closest points past an end: the closest points of the segments the
    // fibres cover, and n_cross along the line between them (from J to I).
    const V r = cI - cJ;
    const T b = tI.dot(tJ), dI = tI.dot(r), dJ = tJ.dot(r), den = 1 - b * b;
    const auto clampTo = [](const T& x, double lo, double hi) {
      return x < lo ? T(lo) : x > hi ? T(hi) : x;
    };
    if (den > 0) {
      // one expression for both, so that swapping I and J swaps them bit for bit
      const auto along = [&](const T& u, const T& v) { return T((b * u - v) / den); };
      const T lambda = along(dJ, dI), mu = -along(dI, dJ);
      const bool inI = !(lambda < -room.I0) && !(lambda > room.I1);
      const bool inJ = !(mu < -room.J0) && !(mu > room.J1);
      if (!inI || !inJ) {
        // a convex quadratic's minimum on the box lies on an edge: one point held at an end of
        // its segment, the other the best for it (lambda b + dJ on J, mu b - dI on I), clamped
        V v = V::Constant(T(HUGE_VAL));
        const auto keep = [&](const T& l, const T& m) {
          const V c = r + l * tI - m * tJ;
          if (c.squaredNorm() < v.squaredNorm()) v = c;
        };
        for (const double l : {-room.I0, room.I1})
          if (std::isfinite(l)) keep(T(l), clampTo(l * b + dJ, -room.J0, room.J1));
        for (const double m : {-room.J0, room.J1})
          if (std::isfinite(m)) keep(clampTo(m * b - dI, -room.I0, room.I1), T(m));
        if (v.norm() > 1e-9 * (RI + RJ)) cross = v.normalized();
      }
    }
  }
  NormalOf<T> out{V::Zero(), valueOf(theta), valueOf(w), false};
  const bool centresApart = d.norm() > 1e-9 * (RI + RJ);
  if (w == 1 || (w > 0 && !centresApart)) {
    out.normal = cross;
    out.crossWeight = 1;
  } else if (centresApart) {
    out.normal = (w * cross + (1 - w) * d.normalized()).normalized();
  } else {
    const V p = xJ - xI;
    out.normal = p.norm() > 0 ? V(p.normalized()) : V(g1I.normalized().template cast<T>());
    out.fallback = true;
  }
  return out;
}

// Eqs. 10-11 for one pair of sections and particles (radii RI, RJ, mm). With kEndFaceI in
// `flags` (ContactFallback) I's particle lies on I's flat end face and N is normal to J's axis
// through it, N = P_tJ (x^I - x0J) / |...|; kEndFaceJ likewise with N = P_tI (x0I - x^J) / |...|.
// `room`: the fibres' arc length beyond the sections (endRoom), for crossings past an end.
NormalGap normalAndGap(const Section& I, const Section& J, const double xiI[2],
                       const double xiJ[2], double RI, double RJ, double thetaParallel,
                       double thetaCross, std::uint8_t flags = 0, const EndRoom& room = {});

// A forced normal N (unit) and the gap gN = (xI(xi_I) - xJ(xi_J)).N + allowance (mm, the
// overlap the step still allows: ContactParams::forcedAllowance); theta as above, crossWeight 0.
NormalGap forcedNormalAndGap(const Section& I, const Section& J, const double xiI[2],
                             const double xiJ[2], const Vec3& N, double allowance);

// Loop B: eqs. 10-11 (or the forced normal) again at the state q for the same particles; the
// friction reference's slip g_rev,0 re-projected onto the new tangent plane; stats.normalTurn =
// the largest angle a normal turned by, rad.
void updateNormalsAndGaps(const FibreStore& fs, const Eigen::VectorXd& q,
                          const ContactParams& params, ContactElementStore& elements,
                          ContactLoopStats& stats, Trace* trace);

}  // namespace fibra
