// Zone builder: the proximity zones of every candidate fibre pair (paper eq. 4).
//
// Reads  FibreStore, ContactParams, CentrelineStore and the broadphase candidate pairs, the
//        cancel flag (per fibre chunk).
// Writes ZoneStore (fibres, intervals, minimum distance, test-point count; id, previous, the
//        penalties, `refined` (0 here) and the element fields are left for zone identity,
//        systems/zone_penalty.h and the element generator), ZoneCache scratch.
// Threading: parallel over fixed chunks of fibres I; each chunk writes its own zone list, the
//        lists are concatenated in chunk order: zones come out sorted by (I, J, sI1) whatever
//        the thread count.
//
// For a fibre pair I < J (or I = J under self-contact, the lower-s side being I), test points
// s_k = k l_zp, l_zp = h_I / m (systems/contact_params.h), are taken on the elements of I that
// have candidates on J; each is projected on the candidate elements of J (closest point:
// orthogonal projection on an element or an element end, systems/contact_geometry.h; for
// self-contact only s' >= s_k + separation). A test point is proximate when that distance is
// <= Delta_prox(I, J); a zone is a maximal run of consecutive proximate test points:
//   Z = ([s_k1, s_k2], [s*_k1, s*_k2]),   |x_I(s_k) - x_J(s*_k)| <= Delta_prox, k1 <= k <= k2.
// Skipping elements without candidates loses nothing: every centreline point within Delta_prox
// of such an element's points would have made a candidate (systems/broadphase.h), and a test
// point shared by two elements is tested once, with the first. The closest point is the
// global one over J whenever it is within Delta_prox (all such points are candidates); ties go
// to the smaller s*. A zone with one test point has sI1 = sI2 (zero length).
#pragma once

#include "components/contact_cache.h"
#include "core/cancel.h"
#include "core/trace.h"
#include "systems/contact_params.h"

namespace fibra {

// Cancelled (checked per fibre chunk): returns early with some chunks' zones missing.
void buildZones(const FibreStore& fs, const ContactParams& params,
                const CentrelineStore& centrelines, const BroadphaseCache& broadphase,
                ZoneCache& cache, ZoneStore& zones, Trace* trace, const Cancel& cancel);

}  // namespace fibra
