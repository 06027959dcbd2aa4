// Contact detection pipeline (paper section 3): one call per contact iteration (the paper's
// loop A) runs, in order,
//   1. broadphase        systems/broadphase.h        candidate element pairs (skin-cached)
//   2. zone builder      systems/zone_builder.h      proximity zones, eq. 4
//   3. zone identity     systems/zone_identity.h     persistent zone ids
//   4. element generator systems/contact_elements.h  intermediate geometry, eqs. 5-9
//   5. normals and gaps  systems/contact_normals.h   eqs. 10-11
// on the fibres at state q, into `zones` and `elements` (overwritten).
//
// Reads  FibreStore, q, ContactParams. Writes ZoneStore, ContactElementStore, ContactCache.
// Threading: every stage is parallel inside (oneTBB), in the caller's task arena; the stores are
//        bitwise identical for every thread count. One cache per assembly; a cache must not be
//        used by two detections at once. No global state.
// Profiling: each stage records a Span (named as above, with its item count) into `trace`
//        when it is not null.
//
//   fibra::ContactParams params = fibra::resolveContactParams(fibres, scene.contact);
//   fibra::ContactCache cache;                 // keep it: candidate set, zone ids
//   fibra::ZoneStore zones;
//   fibra::ContactElementStore elements;
//   fibra::detectContacts(fibres, q, params, cache, zones, elements, trace);
#pragma once

#include "components/contact_cache.h"
#include "core/trace.h"
#include "systems/contact_params.h"

namespace fibra {

struct ContactDetectionReport {
  bool broadphaseRebuilt = false;  // the candidate set was rebuilt (skin exceeded or first call)
  Index candidatePairs = 0;        // candidate element pairs
  Index zones = 0;
  Index elements = 0;
};

ContactDetectionReport detectContacts(const FibreStore& fs, const Eigen::VectorXd& q,
                                      const ContactParams& params, ContactCache& cache,
                                      ZoneStore& zones, ContactElementStore& elements,
                                      Trace* trace = nullptr);

}  // namespace fibra
