// CGAL peer broadphase (bench/peers/peer_broadphase.h): box_self_intersection_d, closed boxes.
#include "bench/peers/peer_broadphase.h"

#include <CGAL/box_intersection_d.h>
#include <tbb/enumerable_thread_specific.h>

namespace fibra::peers {
namespace {

// A box with the element index as its CGAL id (Box_traits_d reads min_coord, max_coord, id).
struct ElementBox {
  using NT = float;
  using ID = std::size_t;
  float lo[3], hi[3];
  std::size_t element;
  static int dimension() { return 3; }
  float min_coord(int d) const { return lo[d]; }
  float max_coord(int d) const { return hi[d]; }
  std::size_t id() const { return element; }
};

}  // namespace

PairList cgalPairs(const std::vector<BoxF>& box, const std::vector<Index>& fibre, bool parallel) {
  std::vector<ElementBox> boxes(box.size());
  for (std::size_t e = 0; e < box.size(); ++e) {
    for (int k = 0; k < 3; ++k) boxes[e].lo[k] = box[e].lo[k], boxes[e].hi[k] = box[e].hi[k];
    boxes[e].element = e;
  }
  tbb::enumerable_thread_specific<PairList> local;
  auto report = [&](const ElementBox& a, const ElementBox& b) {
    if (fibre[a.element] != fibre[b.element])
      local.local().push_back(pairKey(Index(a.element), Index(b.element)));
  };
  if (parallel)
    CGAL::box_self_intersection_d<CGAL::Parallel_tag>(boxes.begin(), boxes.end(), report);
  else
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), report);
  PairList out;
  for (const PairList& l : local) out.insert(out.end(), l.begin(), l.end());
  return out;
}

}  // namespace fibra::peers
