// Contact detection pipeline (paper section 3): one pass per contact iteration (the paper's
// loop A) runs, in order,
//   1. broadphase        systems/broadphase.h        candidate element pairs (skin-cached)
//   2. zone builder      systems/zone_builder.h      proximity zones, eq. 4 (into the cache)
//   3. zone identity     systems/zone_identity.h     persistent ids against the previous zones
//   4. adopt zones       below                       the new zones replace the previous ones
//   5. element generator systems/contact_elements.h  intermediate geometry, eqs. 5-9, with
//                                                    normals and gaps, eqs. 10-11
// on the fibres at state q. The world runs these stages as nodes of its detection graph
// (engine/pipeline.cpp), with the zone penalties (systems/zone_penalty.h) between 3 and 4 and
// the particle and clique binding after 5; detectContacts below runs the detection alone, in the
// same order, for tests, benches and embedders that want only the geometry.
//
// Reads  FibreStore, q, ContactParams, the previous zones. Writes ZoneStore, ContactElementStore,
//        ContactCache.
// Threading: every stage is parallel inside (oneTBB), in the caller's task arena; the stores are
//        bitwise identical for every thread count. One cache per assembly; a cache must not be
//        used by two detections at once. No global state.
// Profiling: each stage records a Span (named as above, with its item count) into `trace`
//        when it is not null.
//
//   fibra::ContactParams params = fibra::resolveContactParams(fibres, scene.contact);
//   fibra::ContactCache cache;                 // keep it: candidate set, scratch
//   fibra::ZoneStore zones;                    // keep it: the previous zones give the ids
//   fibra::ContactElementStore elements;
//   fibra::detectContacts(fibres, q, params, cache, zones, elements, trace);
#pragma once

#include "components/contact_cache.h"
#include "components/contact_params.h"
#include "core/trace.h"

namespace fibra {

struct ContactDetectionReport {
  bool broadphaseRebuilt = false;  // the candidate set was rebuilt (skin exceeded or first call)
  Index candidatePairs = 0;        // candidate element pairs
  Index zones = 0;
  Index elements = 0;
};

// `zones` holds the previous call's zones on entry (identity), this call's on return.
ContactDetectionReport detectContacts(const FibreStore& fs, const Eigen::VectorXd& q,
                                      const ContactParams& params, ContactCache& cache,
                                      ZoneStore& zones, ContactElementStore& elements,
                                      Trace* trace = nullptr);

// Stage 4: the built zones become the current ones (a swap: the previous zones become the
// builder's scratch for the next call).
void adoptZones(ZoneStore& built, ZoneStore& zones);

}  // namespace fibra
