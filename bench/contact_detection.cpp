// Contact detection bench (systems/contact_detection.h): wall time per stage - broadphase (grid
// build and query), zones (eq. 4), zone identity, contact elements (eqs. 5-9, with their first
// normals), a normal update (eqs. 10-11, loop B) - and in total, with 1 and 2 threads, on random
// mats of 10^3 to 10^6 elements and on the paper's woven fabric (480 x 40) and twisted yarn
// (250 x 15). Medians over repeats of a full rebuild (grid included), and of a re-detection after
// a small motion within the skin (candidate set reused). Checks: 1- and 2-thread stores bitwise
// equal; the candidate pairs against an all-pairs box test (up to 2 10^4 elements); zones and
// contact elements against the brute-force reference of tests/contact_reference.h (up to
// --reference-max elements); the broadphase against CGAL and Bullet on the same boxes, when built
// in (bench/peers.cmake), with the same pair set.
//
//   build/bench_contact_detection [--repeats N] [--max-elements N] [--reference-max N]
//                                 [--csv FILE] [--trace FILE] [--no-peers]
// --trace FILE writes one 2-thread detection (full rebuild) and normal update per assembly as a
// Chrome trace (open in Perfetto) and FILE.stages.csv, as `fibra run --trace` does.
#include "core/allocator.h"
#include "bench/bench_util.h"
#include "bench/contact_assemblies.h"
#include "systems/contact_detection.h"
#include "systems/contact_normals.h"
#include "tests/contact_fixtures.h"
#include "tests/contact_reference.h"
#if defined(FIBRA_HAVE_CGAL) || defined(FIBRA_HAVE_BULLET)
#include "bench/peers/peer_broadphase.h"
#endif

#include <tbb/task_arena.h>

#include <cstring>
#include <map>
#include <memory>

using namespace fibra;

namespace {

using Stages = std::map<std::string, double>;  // span name -> ms (summed over one call)

// The spans of one detection call (systems/*.cpp) in table order, with their column heads.
const std::vector<std::pair<const char*, const char*>> kColumns = {
    {"contact-broadphase", "broadphase"}, {"broadphase-grid", "grid"},
    {"broadphase-query", "query"},        {"contact-zones", "zones"},
    {"contact-zone-identity", "identity"}, {"contact-elements", "elements"},
    {"contact-normals", "normals"},        {"contact-detection", "total"}};

struct Options {
  int repeats = 7;
  long maxElements = 1000000;
  long referenceMax = 1000;
  std::string csv = "contact_detection.csv";
  std::string trace;  // Chrome trace JSON of one 2-thread detection per assembly (+ stage CSV)
  bool peers = true;
};

struct Assembly {
  std::string name;
  FibreStore fs;
};

struct Measured {
  Stages rebuild;          // medians per span, full rebuild
  Stages movedRebuild;     // medians per span, full rebuild at a state moved within the skin
  Stages reuse;            // medians per span, the same with the candidate set reused
  ContactDetectionReport report;
  ZoneStore zones;
  ContactElementStore el;
  std::vector<BoxF> box;   // the broadphase boxes and candidates of the last rebuild
  std::vector<Index> candidateFirst, candidate;
};

Stages stagesOf(const Trace& trace) {
  Stages s;
  for (const Trace::Event& e : trace.events())
    s[e.name] += std::chrono::duration<double, std::milli>(e.end - e.begin).count();
  return s;
}

Stages medians(const std::vector<Stages>& runs) {
  Stages out;
  for (const auto& [name, head] : kColumns) {
    std::vector<double> v;
    for (const Stages& r : runs) v.push_back(r.count(name) ? r.at(name) : 0.0);
    std::sort(v.begin(), v.end());
    out[name] = v[v.size() / 2];
  }
  return out;
}

// The state with every node moved by up to `amplitude` per component (mm), seeded.
Eigen::VectorXd moved(const FibreStore& fs, unsigned seed, double amplitude) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd q = fs.q;
  for (Index n = 0; n < fs.nodes(); ++n) x0Of(q, n) += amplitude * Vec3(u(rng), u(rng), u(rng));
  return q;
}

// Medians of `repeats` detections. With `profile`, one more full detection and normal update
// are recorded into it under a span named `label`.
Measured measure(const FibreStore& fs, const ContactParams& p, int threads, int repeats,
                 Trace* profile, const char* label) {
  tbb::task_arena arena(threads);
  Measured m;
  arena.execute([&] {
    ContactCache cache;
    Trace trace;
    detectContacts(fs, fs.q, p, cache, m.zones, m.el);  // warm-up: first touch of the buffers
    std::vector<Stages> runs;
    for (int i = 0; i < repeats; ++i) {
      cache.broadphase.valid = false;  // force a full rebuild, grid included
      trace.clear();
      m.report = detectContacts(fs, fs.q, p, cache, m.zones, m.el, &trace);
      ContactLoopStats stats;
      updateNormalsAndGaps(fs, fs.q, p, m.el, stats, &trace);
      runs.push_back(stagesOf(trace));
    }
    m.rebuild = medians(runs);
    m.box = cache.broadphase.box;
    m.candidateFirst = cache.broadphase.candidateFirst;
    m.candidate = cache.broadphase.candidate;
    // Two states within the skin of fs.q (each node moves < skin / 4): detection there with a
    // full rebuild, then with the candidate set of a rebuild at fs.q reused.
    const Eigen::VectorXd q[2] = {moved(fs, 1, p.skin / 8), moved(fs, 2, p.skin / 8)};
    ZoneStore zones;
    ContactElementStore el;
    runs.clear();
    for (int i = 0; i < repeats; ++i) {
      cache.broadphase.valid = false;
      trace.clear();
      detectContacts(fs, q[i % 2], p, cache, zones, el, &trace);
      runs.push_back(stagesOf(trace));
    }
    m.movedRebuild = medians(runs);
    detectContacts(fs, fs.q, p, cache, zones, el);
    runs.clear();
    for (int i = 0; i < repeats; ++i) {
      trace.clear();
      const ContactDetectionReport r = detectContacts(fs, q[i % 2], p, cache, zones, el, &trace);
      if (r.broadphaseRebuilt) std::fprintf(stderr, "unexpected broadphase rebuild\n");
      runs.push_back(stagesOf(trace));
    }
    m.reuse = medians(runs);
    if (profile) {
      Span span(profile, label, "bench");
      cache.broadphase.valid = false;
      detectContacts(fs, fs.q, p, cache, zones, el, profile);
      ContactLoopStats stats;
      updateNormalsAndGaps(fs, fs.q, p, el, stats, profile);
    }
  });
  return m;
}

std::vector<std::uint64_t> ourPairs(const Measured& m) {
  std::vector<std::uint64_t> pairs;
  for (Index a = 0; a + 1 < Index(m.candidateFirst.size()); ++a)
    for (Index c = m.candidateFirst[a]; c < m.candidateFirst[a + 1]; ++c)
      pairs.push_back(std::uint64_t(a) << 32 | std::uint32_t(m.candidate[c]));
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// All pairs of overlapping closed boxes on distinct fibres, O(n^2).
std::vector<std::uint64_t> allPairs(const FibreStore& fs, const std::vector<BoxF>& box) {
  std::vector<std::uint64_t> pairs;
  for (Index a = 0; a < Index(box.size()); ++a)
    for (Index b = a + 1; b < Index(box.size()); ++b) {
      bool hit = fs.elementFibre[a] != fs.elementFibre[b];
      for (int k = 0; k < 3 && hit; ++k) hit = box[a].lo[k] <= box[b].hi[k] && box[b].lo[k] <= box[a].hi[k];
      if (hit) pairs.push_back(std::uint64_t(a) << 32 | std::uint32_t(b));
    }
  return pairs;
}

// Zones and contact elements against tests/contact_reference.h; prints and returns whether all
// checked values agree (zones: fibres, sI exactly, sJ within 1e-9 mm, test points; elements of
// unambiguous zones: count, sections within 1e-8 mm, particles within 1e-8 mm, gap within 1e-8).
bool checkReference(const FibreStore& fs, const ContactParams& p, const Measured& m) {
  reference::Detection ref;
  const double tz = bench::seconds([&] { ref = reference::detect(fs, fs.q, p); });
  bool ok = Index(ref.zones.size()) == m.zones.size();
  Index checked = 0, mismatched = 0, skipped = 0;
  const double te = bench::seconds([&] {
    for (Index z = 0; ok && z < m.zones.size(); ++z) {
      const reference::Zone& r = ref.zones[z];
      ok = r.I == m.zones.fibreI[z] && r.J == m.zones.fibreJ[z] && r.sI1 == m.zones.sI1[z] &&
           r.sI2 == m.zones.sI2[z] && std::abs(r.sJ1 - m.zones.sJ1[z]) <= 1e-9 &&
           std::abs(r.sJ2 - m.zones.sJ2[z]) <= 1e-9 && r.testPoints == m.zones.testPoints[z];
      bool ambiguous = false;
      const std::vector<reference::Element> re = reference::elements(fs, fs.q, p, r, ambiguous);
      if (ambiguous) { ++skipped; continue; }
      if (Index(re.size()) != m.zones.elementCount[z]) { ++mismatched; continue; }
      for (Index k = 0; k < Index(re.size()); ++k) {
        const Index e = m.zones.firstElement[z] + k;
        if (re[k].ambiguous) { ++skipped; continue; }
        ++checked;
        const double d = std::max({std::abs(re[k].sI - m.el.sI[e]), std::abs(re[k].sJ - m.el.sJ[e]),
                                   std::abs(re[k].xiI[0] - m.el.xiI1[e]), std::abs(re[k].xiI[1] - m.el.xiI2[e]),
                                   std::abs(re[k].xiJ[0] - m.el.xiJ1[e]), std::abs(re[k].xiJ[1] - m.el.xiJ2[e]),
                                   std::abs(re[k].gap - m.el.gap[e])});
        mismatched += d > 1e-8;
      }
    }
  });
  std::printf("  reference: zones %s (%zu, %d test points on the Delta_prox boundary), elements "
              "checked %d, mismatched %d, skipped as ambiguous %d; reference time %.2f s zones + "
              "%.2f s elements\n",
              ok ? "equal" : "DIFFER", ref.zones.size(), ref.ambiguousPoints, checked, mismatched,
              skipped, tz, te);
  return ok && mismatched == 0;
}

struct PeerTimes {
  double cgal = NAN, cgalParallel = NAN, bullet = NAN;  // ms
};

// The broadphase of CGAL and Bullet on the boxes of our last rebuild: medians of `repeats` runs;
// each peer's pair set must equal ours.
PeerTimes runPeers(const FibreStore& fs, const Measured& m, const std::vector<std::uint64_t>& ours,
                   int repeats) {
  PeerTimes t;
#if defined(FIBRA_HAVE_CGAL) || defined(FIBRA_HAVE_BULLET)
  auto timed = [&](const char* name, const std::function<peers::PairList()>& run) {
    peers::PairList pairs;
    const double ms = 1e3 * bench::median(repeats, [&] { pairs = run(); });
    std::sort(pairs.begin(), pairs.end());
    std::printf("  %-14s %10.2f ms, pairs %s\n", name, ms, pairs == ours ? "equal" : "DIFFER");
    return ms;
  };
#endif
#ifdef FIBRA_HAVE_CGAL
  t.cgal = timed("CGAL", [&] { return peers::cgalPairs(m.box, fs.elementFibre, false); });
  tbb::task_arena two(2);
  two.execute([&] {
    t.cgalParallel = timed("CGAL parallel", [&] { return peers::cgalPairs(m.box, fs.elementFibre, true); });
  });
#endif
#ifdef FIBRA_HAVE_BULLET
  t.bullet = timed("Bullet btDbvt", [&] { return peers::bulletPairs(m.box, fs.elementFibre); });
#endif
  return t;
}

std::vector<Assembly> benchAssemblies(const Options& o) {
  std::vector<Assembly> out;
  for (long n = 1000; n <= o.maxElements; n *= 10)
    out.push_back({"mat-" + std::to_string(n),
                   assemblies::randomMat(int(n / 10), 10, 1.0, 0.01, 0.15, 1, 0.3)});
  out.push_back({"woven-480x40", assemblies::wovenFabric()});
  out.push_back({"yarn-250x15", assemblies::twistedYarn()});
  return out;
}

void printHeader() {
  std::printf("%-14s %8s %3s %9s %8s %8s", "assembly", "elements", "thr", "pairs", "zones", "contacts");
  for (const auto& [name, head] : kColumns) std::printf(" %9s", head);
  std::printf(" | %9s %9s %9s %9s\n", "mv-total", "mv-bp", "reuse", "reuse-bp");
}

// The machine's 1, 5 and 15 minute load averages: other work running beside the bench.
std::string loadAverage() {
  char buf[64] = "?";
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (!std::fgets(buf, sizeof buf, f)) buf[0] = 0;
    std::fclose(f);
  }
  std::string s(buf);
  return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const bool more = i + 1 < argc;
    if (!std::strcmp(argv[i], "--repeats") && more) o.repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--max-elements") && more) o.maxElements = std::atol(argv[++i]);
    else if (!std::strcmp(argv[i], "--reference-max") && more) o.referenceMax = std::atol(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && more) o.csv = argv[++i];
    else if (!std::strcmp(argv[i], "--trace") && more) o.trace = argv[++i];
    else if (!std::strcmp(argv[i], "--no-peers")) o.peers = false;
    else {
      std::fprintf(stderr, "usage: bench_contact_detection [--repeats N] [--max-elements N] "
                           "[--reference-max N] [--csv FILE] [--trace FILE] [--no-peers]\n");
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  fibra::fixAllocatorThreshold();  // core/allocator.h
  const Options o = parse(argc, argv);
  std::printf("load average at start: %s\n", loadAverage().c_str());
  std::string header = "assembly,elements,threads,pairs,zones,contacts";
  for (const auto& [name, head] : kColumns) header.append(",").append(head).append("_ms");
  header += ",moved_total_ms,moved_broadphase_ms,reuse_total_ms,reuse_broadphase_ms,cgal_ms,"
            "cgal_parallel_ms,bullet_ms";
  std::FILE* csv = bench::openCsv(o.csv, header.c_str());
  bool allOk = true;
  std::unique_ptr<Trace> profile = o.trace.empty() ? nullptr : std::make_unique<Trace>();
  std::vector<Assembly> all = benchAssemblies(o);  // outlives the trace: spans name them
  for (Assembly& a : all) {
    const ContactParams p = resolveContactParams(a.fs, ContactDef{});
    const int repeats = a.fs.elements() >= 1000000 ? std::min(o.repeats, 3) : o.repeats;
    std::printf("\n%s: %d fibres, %d elements, skin %.4g mm, %d repeats\n", a.name.c_str(),
                a.fs.fibres(), a.fs.elements(), p.skin, repeats);
    printHeader();
    Measured m[2];
    for (int t = 1; t <= 2; ++t) {
      m[t - 1] = measure(a.fs, p, t, repeats, t == 2 ? profile.get() : nullptr, a.name.c_str());
      const Measured& r = m[t - 1];
      std::printf("%-14s %8d %3d %9d %8d %8d", a.name.c_str(), a.fs.elements(), t,
                  r.report.candidatePairs, r.report.zones, r.report.elements);
      for (const auto& [name, head] : kColumns) std::printf(" %9.3f", r.rebuild.at(name));
      std::printf(" | %9.3f %9.3f %9.3f %9.3f\n", r.movedRebuild.at("contact-detection"),
                  r.movedRebuild.at("contact-broadphase"), r.reuse.at("contact-detection"),
                  r.reuse.at("contact-broadphase"));
    }
    const bool same = fixtures::sameBits(m[0].zones, m[1].zones) && fixtures::sameBits(m[0].el, m[1].el);
    std::printf("  1 -> 2 threads: total %.2fx, broadphase %.2fx; stores %s\n",
                m[0].rebuild.at("contact-detection") / m[1].rebuild.at("contact-detection"),
                m[0].rebuild.at("contact-broadphase") / m[1].rebuild.at("contact-broadphase"),
                same ? "bitwise equal" : "DIFFER");
    allOk &= same;
    const std::vector<std::uint64_t> ours = ourPairs(m[0]);
    if (a.fs.elements() <= 20000) {
      std::vector<std::uint64_t> brute;
      const double s = bench::seconds([&] { brute = allPairs(a.fs, m[0].box); });
      std::printf("  all-pairs box test: %.2f s, pairs %s\n", s, brute == ours ? "equal" : "DIFFER");
      allOk &= brute == ours;
    }
    if (a.fs.elements() <= o.referenceMax) allOk &= checkReference(a.fs, p, m[0]);
    PeerTimes peer;
    if (o.peers) peer = runPeers(a.fs, m[0], ours, std::max(1, std::min(repeats, 5)));
    for (int t = 1; t <= 2 && csv; ++t) {
      const Measured& r = m[t - 1];
      std::fprintf(csv, "%s,%d,%d,%d,%d,%d", a.name.c_str(), a.fs.elements(), t,
                   r.report.candidatePairs, r.report.zones, r.report.elements);
      for (const auto& [name, head] : kColumns) std::fprintf(csv, ",%.4f", r.rebuild.at(name));
      std::fprintf(csv, ",%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.movedRebuild.at("contact-detection"),
                   r.movedRebuild.at("contact-broadphase"), r.reuse.at("contact-detection"),
                   r.reuse.at("contact-broadphase"), peer.cgal, peer.cgalParallel, peer.bullet);
      std::fflush(csv);
    }
  }
  if (csv) std::fclose(csv);
  if (profile) {
    profile->writeChromeJson(o.trace);
    profile->writeStageCsv(o.trace + ".stages.csv");
  }
  std::printf("\nload average at end: %s\nchecks: %s\n", loadAverage().c_str(),
              allOk ? "all passed" : "SOME FAILED");
  return allOk ? 0 : 1;
}
