// Contact detection caches: what the detection systems keep between calls (the broadphase's
// candidate set and skin reference) and their reusable scratch buffers; nothing the results
// depend on (the previous zones, for identity, are the caller's: components/contact_state.h).
// Owned by the caller (the world, a bench, a test), one per assembly; never shared between
// concurrent detections. Buffers keep their capacity across calls so that a detection in steady
// state allocates nothing. No logic here.
#pragma once

#include "components/contact.h"

#include <tbb/enumerable_thread_specific.h>

#include <array>
#include <cstdint>
#include <vector>

namespace fibra {

// The centreline of an element as a polynomial of its parameter z in [-1, 1]:
// x0(z) = a + b z + c z^2 (mm); c = 0 for linear elements.
struct CentrelinePolynomial {
  Vec3 a, b, c;
};

struct BoxD {  // axis-aligned box, mm
  Vec3 lo, hi;
};

struct BoxF {  // axis-aligned box in single precision, rounded outwards, mm
  float lo[3], hi[3];
};

// The current centreline geometry, recomputed by the broadphase on every call.
struct CentrelineStore {
  // --- per element ---
  std::vector<CentrelinePolynomial> poly;  // x0(z) of the current state, mm
  std::vector<BoxD> hull;  // box of the Bernstein control points (contains the element), mm
};

struct BroadphaseCache {
  // --- per element, at the last rebuild ---
  std::vector<BoxF> box;  // control-point box inflated by reach + skin margin, mm
  // --- per node, at the last rebuild ---
  std::vector<Vec3> nodeRef;  // centroid x0, mm (skin test: rebuild when one moved > skin/2)
  // --- candidate element pairs (A, B), A < B, as rows per element A ---
  std::vector<Index> candidateFirst;  // per element + 1: first candidate of A
  std::vector<Index> candidate;       // element B of each pair
  // --- uniform grid of the last rebuild ---
  double cellSize = 0;                // mm
  Vec3 origin = Vec3::Zero();         // corner of cell (0, 0, 0), mm
  std::int64_t dims[3] = {0, 0, 0};   // cells along x, y, z
  bool dense = true;                  // cell = bucket (else hashed into `buckets` buckets)
  std::int64_t buckets = 0;
  std::vector<Index> bucketFirst;     // per bucket + 1: first entry
  std::vector<Index> bucketEntry;     // elements of each bucket, ascending
  std::array<std::vector<float>, 6> bucketBound;  // per entry: its element's box as planes
                                      // lo x, lo y, lo z, hi x, hi y, hi z (vector scans), mm
  std::vector<std::int32_t> cellLo;   // per element: 3 cell indices of its box's lower corner
  // --- scratch ---
  std::vector<Index> elementCount;               // per element: candidates found
  tbb::enumerable_thread_specific<std::vector<Index>> hits;  // per worker: overlaps in a cell
  std::vector<std::vector<Index>> chunkCandidate;  // per query chunk: candidates, in order
  // --- state ---
  bool valid = false;                 // a candidate set exists
  bool rebuilt = false;               // the last call rebuilt it
  std::int64_t builds = 0, calls = 0; // counters since creation
  std::vector<double> builtReach;     // per fibre: the reach the boxes were built with, mm
  std::vector<double> builtSeparation;  // per fibre: self-contact separation of the build, mm
  bool builtSelfContact = false;
  double builtSkin = -1;              // mm
  std::vector<Index> bucketCursor;    // scratch of the grid fill
};

// A zone under construction: the fields of ZoneStore that the builder fills.
struct ZoneRecord {
  Index fibreI, fibreJ;
  double sI1, sI2, sJ1, sJ2, minDistance;  // mm
  Index testPoints;
};

// Per-worker scratch of the zone builder: the partner fibres of the fibre being processed.
struct ZonePartner {
  Index fibre = -1;          // partner fibre J
  Index lastElement = -1;    // last element of I whose test points were run against J
  Index currentElement = -1; // element of I whose candidates `candidates` holds
  std::vector<Index> candidates;  // elements of J paired with currentElement
  bool open = false;              // a run of proximate test points is open
  ZoneRecord run{};               // the open run
  std::vector<ZoneRecord> zones;  // closed zones of the pair, by increasing sI1
};

struct ZoneScratch {
  std::vector<Index> slotOfFibre;   // per fibre: partner slot, -1 when not a partner
  std::vector<ZonePartner> partners;  // pool; the first `active` are in use
  Index active = 0;
  std::vector<Index> touched;       // partner slots with candidates at the current element
  std::vector<Index> order;         // partner slots sorted by fibre
};

struct ZoneCache {
  std::vector<std::vector<ZoneRecord>> chunkZones;  // per fibre chunk: zones in canonical order
  tbb::enumerable_thread_specific<ZoneScratch> scratch;
  std::vector<Index> chunkFirst;    // per chunk + 1: first zone
  std::vector<double> matchScore;   // per zone: overlap with its previous match, mm
  std::vector<Index> bestNew;       // per previous zone: the new zone that inherits its id
};

struct ContactCache {
  CentrelineStore centrelines;
  BroadphaseCache broadphase;
  ZoneCache zones;
  ZoneStore builtZones;  // the zones of this call before they replace the previous ones
                         // (systems/contact_detection.h: adoptZones)
};

}  // namespace fibra
