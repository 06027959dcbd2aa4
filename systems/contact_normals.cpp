#include "systems/contact_normals.h"

#include "systems/contact_geometry.h"
#include "systems/friction_history.h"
#include "systems/normal_linearisation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace fibra {

NormalGap normalAndGap(const Section& I, const Section& J, const double xiI[2],
                       const double xiJ[2], double RI, double RJ, double thetaParallel,
                       double thetaCross, std::uint8_t flags, const EndRoom& room) {
  const Vec3 xI = I.x0 + xiI[0] * I.g1 + xiI[1] * I.g2;
  const Vec3 xJ = J.x0 + xiJ[0] * J.g1 + xiJ[1] * J.g2;
  const NormalOf<double> n = normalOfSections<double>(I.x0, J.x0, I.dx0ds, J.dx0ds, xI, xJ, I.g1,
                                                      RI, RJ, thetaParallel, thetaCross, flags,
                                                      room);
  return {n.normal, (xI - xJ).dot(n.normal), n.theta, n.crossWeight, n.fallback};
}

NormalGap forcedNormalAndGap(const Section& I, const Section& J, const double xiI[2],
                             const double xiJ[2], const Vec3& N, double allowance) {
  const Vec3 tI = I.dx0ds.normalized(), tJ = J.dx0ds.normalized();
  const Vec3 xI = I.x0 + xiI[0] * I.g1 + xiI[1] * I.g2;
  const Vec3 xJ = J.x0 + xiJ[0] * J.g1 + xiJ[1] * J.g2;
  const double theta = std::atan2(tI.cross(tJ).norm(), std::abs(tI.dot(tJ)));
  return {N, (xI - xJ).dot(N) + allowance, theta, 0, false};
}

void updateNormalsAndGaps(const FibreStore& fs, const Eigen::VectorXd& q,
                          const ContactParams& params, ContactElementStore& el,
                          ContactLoopStats& stats, Trace* trace) {
  Span span(trace, "contact-normals");
  const Index n = el.size();
  stats.normalTurn = tbb::parallel_reduce(
      tbb::blocked_range<Index>(0, n, 256), 0.0,
      [&](const tbb::blocked_range<Index>& r, double turned) {
        for (Index e = r.begin(); e != r.end(); ++e) {
          const Index fI = el.fibreI[e], fJ = el.fibreJ[e];
          const Section I = contactSection(fs, q, fI, el.sI[e]);
          const Section J = contactSection(fs, q, fJ, el.sJ[e]);
          const double xiI[2] = {el.xiI1[e], el.xiI2[e]}, xiJ[2] = {el.xiJ1[e], el.xiJ2[e]};
          const int forced = el.forced[e];
          const NormalGap ng =
              forced ? forcedNormalAndGap(I, J, xiI, xiJ, forced * params.forcedNormal,
                                          params.forcedAllowance)
                     : normalAndGap(I, J, xiI, xiJ, fs.radius[fI], fs.radius[fJ],
                                    params.thetaParallel, params.thetaCross, el.fallback[e],
                                    endRoom(fs, q, fI, el.sI[e], fJ, el.sJ[e],
                                            params.thetaParallel));
          // A linearised normal already is the state's: only fixed ones can ask for a pass.
          if (!linearisedNormal(params, el, e))
            turned = std::max(turned,
                              std::acos(std::clamp(el.normal[e].dot(ng.normal), -1.0, 1.0)));
          el.normal[e] = ng.normal;
          el.gap[e] = ng.gap;
          el.theta[e] = ng.theta;
          el.crossWeight[e] = ng.crossWeight;
          el.fallback[e] = ng.fallback ? el.fallback[e] | kFallbackNormal
                                       : el.fallback[e] & ~std::uint8_t(kFallbackNormal);
          el.gRev0[e] = projectOnPlane(el.gRev0[e], ng.normal);
        }
        return turned;
      },
      [](double a, double b) { return std::max(a, b); });
  span.items(n);
}

}  // namespace fibra
