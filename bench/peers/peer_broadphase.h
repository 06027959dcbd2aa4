// Peer broadphases for bench/contact_detection.cpp: the candidate element pairs of the same
// inflated element boxes (BroadphaseCache::box) found by CGAL's box_self_intersection_d (a
// streamed segment tree) and by Bullet's dynamic AABB tree (btDbvt, self-collision of one tree).
// Bench only, optional: compiled in by bench/peers.cmake when the Debian packages libcgal-dev and
// libbullet-dev are found (FIBRA_HAVE_CGAL, FIBRA_HAVE_BULLET).
//
// Both report closed-box overlaps (touching boxes overlap, as in systems/broadphase.h) and keep
// pairs on distinct fibres, in the callback, as the grid does; self-contact is off. Pairs come
// back unsorted as A << 32 | B with A < B.
#pragma once

#include "components/contact_cache.h"

#include <cstdint>
#include <vector>

namespace fibra::peers {

using PairList = std::vector<std::uint64_t>;

inline std::uint64_t pairKey(Index a, Index b) {
  return a < b ? std::uint64_t(a) << 32 | std::uint32_t(b) : std::uint64_t(b) << 32 | std::uint32_t(a);
}

// CGAL::box_self_intersection_d on float boxes; `parallel`: CGAL::Parallel_tag (oneTBB, in the
// caller's arena), else the sequential algorithm.
PairList cgalPairs(const std::vector<BoxF>& box, const std::vector<Index>& fibre, bool parallel);

// Bullet btDbvt: every box inserted as a leaf, then collideTT of the tree with itself.
PairList bulletPairs(const std::vector<BoxF>& box, const std::vector<Index>& fibre);

}  // namespace fibra::peers
