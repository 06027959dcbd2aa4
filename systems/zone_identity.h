// Zone identity: gives the zones of this detection call persistent ids by matching them with
// the zones of the previous call, so that per-zone state (the adapted penalty of eq. 13,
// friction bookkeeping) can follow a zone from call to call.
//
// Reads  the previous call's zones (fibres, intervals, ids, nextId), FibreStore and ContactParams
//        (the pair's test-point spacing l_zp).
// Writes the new ZoneStore's id, previous and nextId; ZoneCache scratch (match scores).
// Threading: candidate matches in parallel over zones (each writes its own entries); the id
//        assignment is a sequential pass in zone order, so ids do not depend on thread count.
//
// Rule. New zone z and old zone o match when they join the same fibre pair and their intervals
// overlap or nearly overlap on both fibres:
//   ovI = min(sI2, oI2) - max(sI1, oI1) >= -l_zp  and  ovJ (same on the sorted J intervals) >= -l_zp.
// previous[z] = the match of largest ovI + ovJ (ties: lower index). The old zone's id goes to
// the one new zone, among those whose previous it is, of largest ovI + ovJ (ties: lower index);
// all other zones get fresh ids nextId, nextId + 1, ... in zone order (nextId carried on from the
// previous store). Consequences:
//   small motion: each zone keeps its id;
//   split: the largest part keeps the id, the others get new ids and previous = the parent;
//   merge: the merged zone takes the id of the part it overlaps best; the others' ids end;
//   vanish: an old zone no new zone matches ends with its id; ids are never reused.
#pragma once

#include "components/contact_cache.h"
#include "core/trace.h"
#include "systems/contact_params.h"

namespace fibra {

void matchZones(const FibreStore& fs, const ContactParams& params, const ZoneStore& previous,
                ZoneCache& cache, ZoneStore& zones, Trace* trace);

}  // namespace fibra
