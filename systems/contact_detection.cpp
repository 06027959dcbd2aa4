#include "systems/contact_detection.h"

#include "systems/broadphase.h"
#include "systems/contact_elements.h"
#include "systems/zone_builder.h"
#include "systems/zone_identity.h"

namespace fibra {

void adoptZones(ZoneStore& built, ZoneStore& zones) { std::swap(built, zones); }

ContactDetectionReport detectContacts(const FibreStore& fs, const Eigen::VectorXd& q,
                                      const ContactParams& params, ContactCache& cache,
                                      ZoneStore& zones, ContactElementStore& elements,
                                      Trace* trace) {
  Span span(trace, "contact-detection");
  const Cancel never;
  ContactDetectionReport r;
  r.broadphaseRebuilt =
      updateBroadphase(fs, q, params, cache.centrelines, cache.broadphase, trace, never);
  buildZones(fs, params, cache.centrelines, cache.broadphase, cache.zones, cache.builtZones, trace,
             never);
  matchZones(fs, params, zones, cache.zones, cache.builtZones, trace);
  adoptZones(cache.builtZones, zones);
  generateContactElements(fs, q, params, cache.centrelines, zones, elements, trace, never);
  r.candidatePairs = Index(cache.broadphase.candidate.size());
  r.zones = zones.size();
  r.elements = elements.size();
  span.items(r.elements);
  return r;
}

}  // namespace fibra
