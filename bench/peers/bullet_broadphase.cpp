// Bullet peer broadphase (bench/peers/peer_broadphase.h): btDbvt self-collision, closed boxes.
#include "bench/peers/peer_broadphase.h"

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

#include <cstdint>

namespace fibra::peers {
namespace {

struct Collector : btDbvt::ICollide {
  const std::vector<Index>& fibre;
  PairList& out;
  Collector(const std::vector<Index>& f, PairList& o) : fibre(f), out(o) {}
  void Process(const btDbvtNode* a, const btDbvtNode* b) override {
    const Index ea = Index(reinterpret_cast<std::intptr_t>(a->data));
    const Index eb = Index(reinterpret_cast<std::intptr_t>(b->data));
    if (fibre[ea] != fibre[eb]) out.push_back(pairKey(ea, eb));
  }
};

}  // namespace

PairList bulletPairs(const std::vector<BoxF>& box, const std::vector<Index>& fibre) {
  btDbvt tree;
  for (std::size_t e = 0; e < box.size(); ++e) {
    const BoxF& b = box[e];
    const btDbvtVolume v = btDbvtVolume::FromMM(btVector3(b.lo[0], b.lo[1], b.lo[2]),
                                                btVector3(b.hi[0], b.hi[1], b.hi[2]));
    tree.insert(v, reinterpret_cast<void*>(std::intptr_t(e)));
  }
  PairList out;
  Collector collector(fibre, out);
  tree.collideTT(tree.m_root, tree.m_root, collector);
  return out;
}

}  // namespace fibra::peers
