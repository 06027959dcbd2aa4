#include "systems/broadphase.h"

#include "systems/contact_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <bit>
#include <limits>

namespace fibra {
namespace {

constexpr Index kQueryChunk = 256;  // elements per query chunk (fixed: deterministic output)
constexpr Index kSumChunk = 4096;   // elements per partial sum of the mean extent
constexpr int kLanes = 8;           // boxes screened per vector compare
constexpr double kCellPerExtent = 1.25;  // cell size / mean box extent (measured: fabric, yarn, mat)

float roundDown(double v) {
  const float f = float(v);
  return double(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double v) {
  const float f = float(v);
  return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

template <class F>
void parallelIndex(Index n, Index grain, const F& f) {
  tbb::parallel_for(tbb::blocked_range<Index>(0, n, grain), [&](const tbb::blocked_range<Index>& r) {
    for (Index i = r.begin(); i != r.end(); ++i) f(i);
  });
}

void computeCentrelines(const FibreStore& fs, const Eigen::VectorXd& q, CentrelineStore& cl) {
  const Index n = fs.elements();
  cl.poly.resize(n);
  cl.hull.resize(n);
  parallelIndex(n, 1024, [&](Index e) {
    cl.poly[e] = centrelinePolynomial(fs, q, e);
    cl.hull[e] = controlPointBox(cl.poly[e]);
  });
}

bool sameBuildParams(const FibreStore& fs, const ContactParams& p, const BroadphaseCache& c) {
  return c.valid && Index(c.box.size()) == fs.elements() && Index(c.nodeRef.size()) == fs.nodes() &&
         c.builtReach == p.reach && c.builtSkin == p.skin && c.builtSelfContact == p.selfContact &&
         c.builtSeparation == p.selfSeparation;
}

// True when no node moved more than skin / 2 since the last rebuild.
bool skinHolds(const FibreStore& fs, const Eigen::VectorXd& q, double skin,
               const BroadphaseCache& c) {
  const double limit2 = 0.25 * skin * skin;
  std::atomic<bool> moved{false};
  parallelIndex(fs.nodes(), 4096, [&](Index n) {
    if ((Vec3(x0Of(q, n)) - c.nodeRef[n]).squaredNorm() > limit2) moved.store(true, std::memory_order_relaxed);
  });
  return !moved.load();
}

void buildBoxes(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& p,
                const CentrelineStore& cl, BroadphaseCache& c) {
  const Index n = fs.elements();
  c.box.resize(n);
  parallelIndex(n, 1024, [&](Index e) {
    const Index f = fs.elementFibre[e];
    const double lambda = fs.order[f] == 2 ? 1.25 : 1.0;
    const double r = p.reach[f] + lambda * p.skin / 2;
    BoxF& b = c.box[e];
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = roundDown(cl.hull[e].lo[k] - r);
      b.hi[k] = roundUp(cl.hull[e].hi[k] + r);
    }
  });
  c.nodeRef.resize(fs.nodes());
  parallelIndex(fs.nodes(), 4096, [&](Index k) { c.nodeRef[k] = x0Of(q, k); });
  c.builtReach = p.reach;
  c.builtSkin = p.skin;
  c.builtSelfContact = p.selfContact;
  c.builtSeparation = p.selfSeparation;
}

// Grid geometry: cell size = mean largest box extent, origin = lower corner of all boxes.
void sizeGrid(BroadphaseCache& c) {
  const Index n = Index(c.box.size());
  const Index chunks = (n + kSumChunk - 1) / kSumChunk;
  std::vector<double> partial(chunks);
  parallelIndex(chunks, 1, [&](Index k) {
    double s = 0;
    for (Index e = k * kSumChunk; e < std::min(n, (k + 1) * kSumChunk); ++e) {
      const BoxF& b = c.box[e];
      s += std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
    }
    partial[k] = s;
  });
  double sum = 0;
  for (double s : partial) sum += s;
  using Bounds = std::pair<Vec3, Vec3>;
  const double inf = std::numeric_limits<double>::infinity();
  const Bounds world = tbb::parallel_reduce(
      tbb::blocked_range<Index>(0, n, 4096), Bounds{Vec3::Constant(inf), Vec3::Constant(-inf)},
      [&](const tbb::blocked_range<Index>& r, Bounds acc) {
        for (Index e = r.begin(); e != r.end(); ++e)
          for (int k = 0; k < 3; ++k) {
            acc.first[k] = std::min(acc.first[k], double(c.box[e].lo[k]));
            acc.second[k] = std::max(acc.second[k], double(c.box[e].hi[k]));
          }
        return acc;
      },
      [](const Bounds& a, const Bounds& b) {
        return Bounds{a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)};
      });
  c.cellSize = std::max(sum / std::max<Index>(n, 1), 1e-12) * kCellPerExtent;
  c.origin = world.first;
  std::int64_t cells = 1;
  for (int k = 0; k < 3; ++k) {
    c.dims[k] = std::int64_t(std::floor((world.second[k] - world.first[k]) / c.cellSize)) + 1;
    cells = cells > (std::int64_t(1) << 40) / c.dims[k] ? (std::int64_t(1) << 40) : cells * c.dims[k];
  }
  c.dense = cells <= 2 * std::int64_t(n) + 64;
  std::int64_t buckets = 64;
  while (buckets < 2 * std::int64_t(n)) buckets *= 2;
  c.buckets = c.dense ? cells : buckets;
}

struct Grid {
  const BroadphaseCache& c;
  double inv;

  std::int64_t cellOf(float x, int k) const {
    const std::int64_t i = std::int64_t(std::floor((double(x) - c.origin[k]) * inv));
    return std::clamp<std::int64_t>(i, 0, c.dims[k] - 1);
  }
  std::int64_t bucketOf(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (c.dense) return x + c.dims[0] * (y + c.dims[1] * z);
    const std::uint64_t h = std::uint64_t(x) * 73856093u ^ std::uint64_t(y) * 19349663u ^
                            std::uint64_t(z) * 83492791u;
    return std::int64_t(h & std::uint64_t(c.buckets - 1));
  }
  // Calls f(bucket, ix, iy, iz) for every cell of box b; in a hashed grid a bucket met twice by
  // the same box is passed only once when `uniqueBuckets`.
  template <class F>
  void forEachCell(const BoxF& b, bool uniqueBuckets, const F& f) const {
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = cellOf(b.lo[k], k), hi[k] = cellOf(b.hi[k], k);
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          const std::int64_t bucket = bucketOf(x, y, z);
          if (uniqueBuckets && !c.dense && seenBefore(lo, hi, x, y, z, bucket)) continue;
          f(bucket, x, y, z);
        }
  }
  // Whether a cell of the box visited before (x, y, z) maps to the same bucket.
  bool seenBefore(const std::int64_t lo[3], const std::int64_t hi[3], std::int64_t x,
                  std::int64_t y, std::int64_t z, std::int64_t bucket) const {
    for (std::int64_t zz = lo[2]; zz <= z; ++zz)
      for (std::int64_t yy = lo[1]; yy <= hi[1]; ++yy)
        for (std::int64_t xx = lo[0]; xx <= hi[0]; ++xx) {
          if (zz == z && yy == y && xx == x) return false;
          if (bucketOf(xx, yy, zz) == bucket) return true;
        }
    return false;
  }
};

// Counting sort of (bucket, element) entries; every bucket's elements ascending.
void fillGrid(BroadphaseCache& c, const Grid& g) {
  const Index n = Index(c.box.size());
  c.bucketFirst.assign(std::size_t(c.buckets) + 1, 0);
  parallelIndex(n, 512, [&](Index e) {
    g.forEachCell(c.box[e], true, [&](std::int64_t b, std::int64_t, std::int64_t, std::int64_t) {
      std::atomic_ref<Index>(c.bucketFirst[b + 1]).fetch_add(1, std::memory_order_relaxed);
    });
  });
  for (std::int64_t b = 0; b < c.buckets; ++b) c.bucketFirst[b + 1] += c.bucketFirst[b];
  c.bucketEntry.resize(c.bucketFirst[c.buckets] + kLanes);  // padded for the vector scans
  c.bucketCursor.assign(c.bucketFirst.begin(), c.bucketFirst.end() - 1);
  parallelIndex(n, 512, [&](Index e) {
    g.forEachCell(c.box[e], true, [&](std::int64_t b, std::int64_t, std::int64_t, std::int64_t) {
      const Index at = std::atomic_ref<Index>(c.bucketCursor[b]).fetch_add(1, std::memory_order_relaxed);
      c.bucketEntry[at] = e;
    });
  });
  for (auto& plane : c.bucketBound) plane.resize(c.bucketEntry.size());
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, c.buckets, 2048),
                    [&](const tbb::blocked_range<std::int64_t>& r) {
                      for (std::int64_t b = r.begin(); b != r.end(); ++b) {
                        std::sort(c.bucketEntry.begin() + c.bucketFirst[b],
                                  c.bucketEntry.begin() + c.bucketFirst[b + 1]);
                        for (Index i = c.bucketFirst[b]; i < c.bucketFirst[b + 1]; ++i)
                          for (int k = 0; k < 3; ++k) {
                            c.bucketBound[k][i] = c.box[c.bucketEntry[i]].lo[k];
                            c.bucketBound[3 + k][i] = c.box[c.bucketEntry[i]].hi[k];
                          }
                      }
                    });
  c.cellLo.resize(3 * std::size_t(n));
  parallelIndex(n, 4096, [&](Index e) {
    for (int k = 0; k < 3; ++k) c.cellLo[3 * e + k] = std::int32_t(g.cellOf(c.box[e].lo[k], k));
  });
}

// First index in [i0, i1) of the ascending `entry` holding a value > A (branch-free search).
Index firstAbove(const Index* entry, Index i0, Index i1, Index A) {
  Index n = i1 - i0;
  if (n == 0) return i0;
  const Index* base = entry + i0;
  while (n > 1) {
    const Index half = n / 2;
    base = base[half] <= A ? base + half : base;
    n -= half;
  }
  return Index(base - entry) + (*base <= A);
}

// Bit l set when A's box (lo a[0..2], hi a[3..5]) overlaps the box of entry j + l, l < kLanes.
#if defined(__AVX__)
struct LaneBox {
  __m256 v[6];
  explicit LaneBox(const BoxF& b) {
    for (int k = 0; k < 3; ++k) v[k] = _mm256_set1_ps(b.lo[k]), v[3 + k] = _mm256_set1_ps(b.hi[k]);
  }
};
inline unsigned overlapLanes(const LaneBox& a, const float* const p[6], Index j) {
  __m256 m = _mm256_cmp_ps(a.v[0], _mm256_loadu_ps(p[3] + j), _CMP_LE_OQ);
  for (int k = 0; k < 3; ++k) {
    if (k > 0) m = _mm256_and_ps(m, _mm256_cmp_ps(a.v[k], _mm256_loadu_ps(p[3 + k] + j), _CMP_LE_OQ));
    m = _mm256_and_ps(m, _mm256_cmp_ps(_mm256_loadu_ps(p[k] + j), a.v[3 + k], _CMP_LE_OQ));
  }
  return unsigned(_mm256_movemask_ps(m));
}
#else
struct LaneBox {
  BoxF b;
  explicit LaneBox(const BoxF& box) : b(box) {}
};
inline unsigned overlapLanes(const LaneBox& a, const float* const p[6], Index j) {
  unsigned m = 0;
  for (int l = 0; l < kLanes; ++l) {
    const Index i = j + l;
    const bool hit = (a.b.lo[0] <= p[3][i]) & (p[0][i] <= a.b.hi[0]) & (a.b.lo[1] <= p[4][i]) &
                     (p[1][i] <= a.b.hi[1]) & (a.b.lo[2] <= p[5][i]) & (p[2][i] <= a.b.hi[2]);
    m |= unsigned(hit) << l;
  }
  return m;
}
#endif

// Appends to `out` the candidates B > A of element A. A cell's entries are first screened
// for box overlap kLanes at a time into `hits`, then filtered: reference cell, fibre rule.
void queryElement(const FibreStore& fs, const ContactParams& p, const BroadphaseCache& c,
                  const Grid& g, Index A, std::vector<Index>& hits, std::vector<Index>& out) {
  const BoxF box = c.box[A];
  const LaneBox lanes(box);
  const float* const planes[6] = {c.bucketBound[0].data(), c.bucketBound[1].data(),
                                  c.bucketBound[2].data(), c.bucketBound[3].data(),
                                  c.bucketBound[4].data(), c.bucketBound[5].data()};
  const Index fA = fs.elementFibre[A];
  const bool self = p.selfContact;
  const double hA = fs.length[fA] / fs.elementCount[fA];
  const double sep = self ? p.selfSeparation[fA] : 0;
  const std::int32_t* cA = &c.cellLo[3 * std::size_t(A)];
  g.forEachCell(box, false, [&](std::int64_t bucket, std::int64_t x, std::int64_t y, std::int64_t z) {
    const Index* entry = c.bucketEntry.data();
    const Index i1 = c.bucketFirst[bucket + 1];
    const Index i0 = firstAbove(entry, c.bucketFirst[bucket], i1, A);
    if (Index(hits.size()) < i1 - i0) hits.resize(i1 - i0);
    Index* h = hits.data();
    Index n = 0;
    for (Index j = i0; j < i1; j += kLanes) {  // planes are padded: reading past i1 is safe
      unsigned m = overlapLanes(lanes, planes, j);
      if (i1 - j < kLanes) m &= (1u << (i1 - j)) - 1;
      for (; m; m &= m - 1) h[n++] = entry[j + std::countr_zero(m)];
    }
    for (Index k = 0; k < n; ++k) {
      const Index B = h[k];
      const std::int32_t* cB = &c.cellLo[3 * std::size_t(B)];
      if (std::max(cA[0], cB[0]) != x || std::max(cA[1], cB[1]) != y || std::max(cA[2], cB[2]) != z)
        continue;
      if (fs.elementFibre[B] == fA && !(self && (B - A + 1) * hA >= sep)) continue;
      out.push_back(B);
    }
  });
}

void queryPairs(const FibreStore& fs, const ContactParams& p, BroadphaseCache& c, const Grid& g,
                const Cancel& cancel) {
  const Index n = Index(c.box.size());
  const Index chunks = (n + kQueryChunk - 1) / kQueryChunk;
  c.chunkCandidate.resize(chunks);
  c.elementCount.resize(n);
  parallelIndex(chunks, 1, [&](Index k) {
    std::vector<Index>& out = c.chunkCandidate[k];
    std::vector<Index>& hits = c.hits.local();
    out.clear();
    if (cancel()) return;
    for (Index A = k * kQueryChunk; A < std::min(n, (k + 1) * kQueryChunk); ++A) {
      const std::size_t before = out.size();
      queryElement(fs, p, c, g, A, hits, out);
      c.elementCount[A] = Index(out.size() - before);
    }
  });
  c.candidateFirst.resize(n + 1);
  c.candidateFirst[0] = 0;
  for (Index e = 0; e < n; ++e) c.candidateFirst[e + 1] = c.candidateFirst[e] + c.elementCount[e];
  c.candidate.resize(c.candidateFirst[n]);
  parallelIndex(chunks, 1, [&](Index k) {
    std::copy(c.chunkCandidate[k].begin(), c.chunkCandidate[k].end(),
              c.candidate.begin() + c.candidateFirst[k * kQueryChunk]);
  });
}

}  // namespace

bool updateBroadphase(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& params,
                      CentrelineStore& centrelines, BroadphaseCache& cache, Trace* trace,
                      const Cancel& cancel) {
  Span span(trace, "contact-broadphase");
  {
    Span s(trace, "broadphase-centrelines");
    computeCentrelines(fs, q, centrelines);
    s.items(fs.elements());
  }
  ++cache.calls;
  bool reuse;
  {
    Span s(trace, "broadphase-skin-test");
    reuse = sameBuildParams(fs, params, cache) && skinHolds(fs, q, params.skin, cache);
    s.items(fs.nodes());
  }
  cache.rebuilt = !reuse;
  if (!reuse) {
    {
      Span s(trace, "broadphase-grid");
      buildBoxes(fs, q, params, centrelines, cache);
      sizeGrid(cache);
      fillGrid(cache, Grid{cache, 1 / cache.cellSize});
      s.items(cache.bucketFirst[cache.buckets]);
    }
    Span s(trace, "broadphase-query");
    queryPairs(fs, params, cache, Grid{cache, 1 / cache.cellSize}, cancel);
    s.items(Index(cache.candidate.size()));
    cache.valid = !cancel.requested();  // a cancelled query left the candidate set incomplete
    ++cache.builds;
  }
  span.items(Index(cache.candidate.size()));
  return cache.rebuilt;
}

}  // namespace fibra
