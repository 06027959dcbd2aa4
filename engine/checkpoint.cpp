// The checkpoint of a world's last converged state (World::saveCheckpoint, restoreCheckpoint).
//
// What an increment carries to the next is all that is written: the positions q, the committed
// contact state (zones with their identities and penalties, contact elements and their forces,
// stick/slip statuses, the friction history of reversible slips), the converged residual and
// external load (reactions), the energy balance and its last forces, the progress through the
// steps (time, step, increment, the adaptive attempt size), and the contact cliques of the
// tangent's pattern (which only grow between prunings, so the pattern depends on the history).
// Everything else is rebuilt from the scene or at the next attempt's first detection (caches,
// the tangent, its pattern from the carried cliques).
//
// Format (binary, this build's byte order and type sizes; a checkpoint is read back by the same
// fibra version on the same kind of machine):
//   "fibra-checkpoint\n", u64 length of the body, the body, u64 FNV-1a of the body.
//   Body: u32 format, the version string, u32 sizeof(Index), u64 scene fingerprint (FNV-1a of
//   the scene's fields but those a user may change to get a stopped run going again), then the
//   fields in a fixed order, each store column by column (core/columns.h reflection): a vector
//   as u64 count then its elements, a dynamic Eigen matrix as i64 rows, cols then its values, a
//   fixed one as its values, a string as u64 length then its bytes, a struct member by member.
// A file that is truncated, corrupt, of another version or of another scene is refused with a
// CheckpointError that says which; nothing of the world is changed then.
#include "core/columns.h"
#include "engine/world_state.h"
#include "fibra/version.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <istream>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace fibra {
namespace {

constexpr char kMagic[] = "fibra-checkpoint\n";
constexpr std::uint32_t kFormat = 8;  // 3: the friction blocks on facing particles; 4: the forced
                                      // signs; 5: the steps of "auto"'s linearised normals; 6: the
                                      // step whose damping_from "failure" continuation is on; 7:
                                      // the step where a kept linearised attempt failed; 8: the
                                      // zones refined to Lobatto elements

template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};

template <class T>
concept DenseMatrix = requires(T& m) {
  m.data();
  m.resize(0, 0);
  typename T::Scalar;
};

void fnv(const void* data, std::size_t n, std::uint64_t& h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
}
constexpr std::uint64_t kFnvStart = 1469598103934665603ull;

struct Writer {
  std::ostream& out;
  void bytes(const void* p, std::size_t n) {
    out.write(static_cast<const char*>(p), std::streamsize(n));
  }
};

struct Reader {
  std::istream& in;
  std::uint64_t remaining;  // bytes left in the body
  void bytes(void* p, std::size_t n) {
    if (n > remaining || !in.read(static_cast<char*>(p), std::streamsize(n)))
      throw CheckpointError("the file is truncated");
    remaining -= n;
  }
  // A count read from the file, checked against what is left of it before anything is
  // allocated (each element takes at least `least` bytes).
  std::size_t count(std::size_t least) {
    std::uint64_t n = 0;
    bytes(&n, sizeof n);
    if (least > 0 && n > remaining / least) throw CheckpointError("the file is corrupt");
    return std::size_t(n);
  }
};

// Writes or reads one value, recursively: arithmetic and enums as their bytes; std::vector
// (count + elements), std::array, dense Eigen matrices (shape + values); aggregates member by
// member. One function for both directions keeps the order the same.
template <class A, class T>
void field(A& a, T& v) {
  constexpr bool reading = std::is_same_v<A, Reader>;
  if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    a.bytes(&v, sizeof v);
  } else if constexpr (std::is_same_v<T, std::string>) {
    if constexpr (reading) {
      v.resize(a.count(1));
    } else {
      std::uint64_t n = v.size();
      a.bytes(&n, sizeof n);
    }
    a.bytes(v.data(), v.size());
  } else if constexpr (IsStdVector<T>::value) {
    using E = typename T::value_type;
    if constexpr (reading) {
      v.resize(a.count(std::is_arithmetic_v<E> ? sizeof(E) : 1));
    } else {
      std::uint64_t n = v.size();
      a.bytes(&n, sizeof n);
    }
    if constexpr (std::is_arithmetic_v<E> && !std::is_same_v<E, bool>)
      a.bytes(v.data(), v.size() * sizeof(E));
    else
      for (auto& e : v) field(a, e);
  } else if constexpr (IsArray<T>::value) {
    for (auto& e : v) field(a, e);
  } else if constexpr (DenseMatrix<T>) {
    if constexpr (T::SizeAtCompileTime > 0) {  // fixed size: the values only
      a.bytes(v.data(), sizeof(typename T::Scalar) * T::SizeAtCompileTime);
    } else {
      std::int64_t shape[2] = {v.rows(), v.cols()};
      a.bytes(shape, sizeof shape);
      if constexpr (reading) {
        const std::uint64_t room = a.remaining / sizeof(typename T::Scalar);
        if (shape[0] < 0 || shape[1] < 0 ||
            (T::RowsAtCompileTime > 0 && shape[0] != T::RowsAtCompileTime) ||
            (T::ColsAtCompileTime > 0 && shape[1] != T::ColsAtCompileTime) ||
            (shape[1] > 0 && std::uint64_t(shape[0]) > room / std::uint64_t(shape[1])))
          throw CheckpointError("the file is corrupt");
        v.resize(shape[0], shape[1]);
      }
      a.bytes(v.data(), std::size_t(v.size()) * sizeof(typename T::Scalar));
    }
  } else {
    static_assert(std::is_aggregate_v<T>, "a store, or a column type the checkpoint can reach");
    forEachColumn(v, [&](auto& member) { field(a, member); });
  }
}

// What the next increment reads of the last converged state, read aside so that a bad file
// leaves the world as it was.
struct Carried {
  double time = 0, dt = 0;
  int step = 0, increment = 0, rateStep = -1, linearisedStep = -1, escalationFailedStep = -1,
      linearisedFailedStep = -1, dampedStep = -1;
  Eigen::VectorXd q, convergedQ, convergedR, convergedFext, rate;
  EnergyStore energy;
  ContactState committed;
  std::vector<std::uint64_t> cliqueKeys;
};

// The carried fields in the file's order.
template <class A>
void carried(A& a, double& time, int& step, int& increment, double& dt, int& rateStep,
             int& linearisedStep, int& escalationFailedStep, int& linearisedFailedStep,
             int& dampedStep,
             Eigen::VectorXd& q, Eigen::VectorXd& convergedQ, Eigen::VectorXd& convergedR,
             Eigen::VectorXd& convergedFext, Eigen::VectorXd& rate, EnergyStore& energy,
             ContactState& committed, std::vector<std::uint64_t>& cliqueKeys) {
  field(a, time), field(a, step), field(a, increment), field(a, dt), field(a, rateStep);
  field(a, linearisedStep), field(a, escalationFailedStep), field(a, linearisedFailedStep);
  field(a, dampedStep);
  field(a, q), field(a, convergedQ), field(a, convergedR), field(a, convergedFext), field(a, rate);
  field(a, energy);
  field(a, committed);
  field(a, cliqueKeys);
}

// The scene a checkpoint belongs to: every field of the scene (after its generators) but those
// a user may change to get a stopped run going again: per step its name, iteration and cutback
// limits, tolerances, line search, predictor, damping (where some step has damping) and
// output_every; the solver; the output but its probes (whose nodes the history's columns name).
std::uint64_t fingerprint(const WorldState& w) {
  SceneDef s = w.scene;
  // Whether some step has damping sets the history's columns (viscous_force): a damping may
  // change, not come or go.
  const bool damped = anyStepDamped(s);
  for (StepDef& st : s.steps) {
    const StepDef d;
    st.name = d.name, st.maxIterations = d.maxIterations, st.maxCutbacks = d.maxCutbacks;
    st.forceTolerance = d.forceTolerance, st.incrementTolerance = d.incrementTolerance;
    st.lineSearch = d.lineSearch, st.damping = d.damping, st.outputEvery = d.outputEvery;
    st.predictor = d.predictor;
  }
  std::vector<ProbeDef> probes = std::move(s.output.probes);
  s.output = OutputDef{};
  s.output.probes = std::move(probes);
  std::ostringstream text;
  Writer a{text};
  // every member but the solver's, so that a solver setting added to a later build leaves the
  // checkpoints of this one readable (not those of builds before this rule)
  forEachColumn(s, [&](auto& member) {
    if constexpr (!std::is_same_v<std::decay_t<decltype(member)>, SolverDef>) field(a, member);
  });
  field(a, damped);
  std::uint64_t h = kFnvStart;
  const std::string bytes = text.str();
  fnv(bytes.data(), bytes.size(), h);
  return h;
}

// v as 16 hexadecimal digits.
std::string hex(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

template <class A, class T>
void header(A& a, T& format, std::string& version, T& indexSize, std::uint64_t& scene) {
  field(a, format);
  std::vector<char> text(version.begin(), version.end());
  field(a, text);
  version.assign(text.begin(), text.end());
  field(a, indexSize);
  field(a, scene);
}

}  // namespace

void saveCheckpoint(const WorldState& w, std::ostream& out) {
  std::ostringstream body;
  Writer a{body};
  std::uint32_t format = kFormat, indexSize = sizeof(Index);
  std::string version = FIBRA_VERSION_STRING;
  std::uint64_t scene = fingerprint(w);
  header(a, format, version, indexSize, scene);
  WorldState& m = const_cast<WorldState&>(w);  // `field` reads and writes through one path
  carried(a, m.time, m.step, m.increment, m.dt, m.rateStep, m.linearisedStep,
          m.escalationFailedStep, m.linearisedFailedStep, m.dampedStep, m.fibres.q, m.converged.q,
          m.converged.r, m.converged.fext, m.rate, m.energy, m.committed, m.cliques.key);
  const std::string text = body.str();
  const std::uint64_t length = text.size();
  std::uint64_t hash = kFnvStart;
  fnv(text.data(), text.size(), hash);
  out.write(kMagic, sizeof kMagic - 1);
  out.write(reinterpret_cast<const char*>(&length), sizeof length);
  out.write(text.data(), std::streamsize(text.size()));
  out.write(reinterpret_cast<const char*>(&hash), sizeof hash);
  if (!out) throw std::runtime_error("the checkpoint could not be written");
}

void restoreCheckpoint(WorldState& s, std::istream& file) {
  const std::streampos start = file.tellg();
  file.seekg(0, std::ios::end);
  const std::uint64_t size = file ? std::uint64_t(file.tellg() - start) : 0;
  file.seekg(start);
  // Magic, length, checksum: a file that is not whole is refused before it is parsed.
  constexpr std::uint64_t magicSize = sizeof kMagic - 1, word = sizeof(std::uint64_t);
  std::string magic(std::min(size, magicSize), '\0');
  file.read(magic.data(), std::streamsize(magic.size()));
  if (!file || magic != std::string(kMagic, magic.size()) || size == 0)
    throw CheckpointError("not a fibra checkpoint");
  std::uint64_t length = 0;
  if (size < magicSize + word || !file.read(reinterpret_cast<char*>(&length), word))
    throw CheckpointError("the file is truncated");
  const std::uint64_t rest = size - magicSize - word;
  if (rest < word || length > rest - word) throw CheckpointError("the file is truncated");
  if (length < rest - word) throw CheckpointError("the file is corrupt (bytes after its end)");
  std::string text(length, '\0');
  std::uint64_t stored = 0, hash = kFnvStart;
  file.read(text.data(), std::streamsize(length));
  file.read(reinterpret_cast<char*>(&stored), word);
  if (!file) throw CheckpointError("the file is truncated");
  fnv(text.data(), text.size(), hash);
  if (hash != stored) throw CheckpointError("the file is corrupt (checksum)");

  std::istringstream in(std::move(text));
  Reader a{in, length};
  std::uint32_t format = 0, indexSize = 0;
  std::string version;
  std::uint64_t scene = 0;
  header(a, format, version, indexSize, scene);
  if (format != kFormat || version != FIBRA_VERSION_STRING || indexSize != sizeof(Index))
    throw CheckpointError("written by fibra " + version + " (format " + std::to_string(format) +
                          "); this is fibra " + FIBRA_VERSION_STRING + " (format " +
                          std::to_string(kFormat) + ")");
  if (scene != fingerprint(s))
    throw CheckpointError(
        "written for another scene: its fibres, materials, groups, boundary conditions, loads, "
        "steps, contact, tools, stabilisation or probes differ, or damping was switched on or "
        "off (only the steps' names, iteration and cutback limits, tolerances, line search, "
        "predictor, damping where some step has it, and output_every, the solver and the "
        "output but its probes may change); or it was written by another build of fibra " +
        std::string(FIBRA_VERSION_STRING) + " whose scene description has other fields (the "
        "fingerprint covers them all but the solver's; the file's is " + hex(scene) +
        ", this scene's " + hex(fingerprint(s)) + ")");
  Carried w;
  carried(a, w.time, w.step, w.increment, w.dt, w.rateStep, w.linearisedStep,
          w.escalationFailedStep, w.linearisedFailedStep, w.dampedStep, w.q, w.convergedQ, w.convergedR,
          w.convergedFext, w.rate, w.energy, w.committed, w.cliqueKeys);
  if (a.remaining != 0) throw CheckpointError("the file is corrupt (bytes after its end)");
  const Index dofs = Index(s.fibres.q.size());
  const int steps = int(s.scene.steps.size());
  if (Index(w.q.size()) != dofs || Index(w.convergedQ.size()) != dofs || w.step < 0 ||
      w.step > steps || w.increment < 0 ||
      (w.step < steps && w.increment >= s.scene.steps[size_t(w.step)].increments) ||
      w.rateStep < -1 || w.rateStep > steps || w.linearisedStep < -1 ||
      w.linearisedStep > steps || w.escalationFailedStep < -1 || w.escalationFailedStep > steps ||
      w.linearisedFailedStep < -1 || w.linearisedFailedStep > steps ||
      w.dampedStep < -1 || w.dampedStep > steps ||
      (w.rateStep >= 0 && Index(w.rate.size()) != dofs))
    throw CheckpointError("the file is corrupt (its progress is not this scene's)");

  s.time = w.time, s.step = w.step, s.increment = w.increment, s.dt = w.dt, s.rateStep = w.rateStep;
  s.linearisedStep = w.linearisedStep, s.escalationFailedStep = w.escalationFailedStep;
  s.linearisedFailedStep = w.linearisedFailedStep;
  s.dampedStep = w.dampedStep;
  s.fibres.q = std::move(w.q);
  s.converged.q = std::move(w.convergedQ);
  s.converged.r = std::move(w.convergedR);
  s.converged.fext = std::move(w.convergedFext);
  s.rate = std::move(w.rate);
  s.energy = std::move(w.energy);
  s.committed = std::move(w.committed);
  s.trial = s.committed;
  s.system.r = s.converged.r;
  s.system.fext = s.converged.fext;
  s.cache.broadphase.valid = false;  // the candidates were found around another state
  // The tangent's pattern holds every contact clique seen since its last pruning
  // (systems/contact_cliques.h), so its ordering, and the factors' round-off, depend on the
  // history: the next detection rebuilds the pattern from the carried cliques.
  s.cliques.key = std::move(w.cliqueKeys);
  s.cliques.elements = s.fibres.elements();
  s.cliques.colourFirst.clear();
}

void World::saveCheckpoint(std::ostream& out) const { fibra::saveCheckpoint(*s_, out); }
void World::restoreCheckpoint(std::istream& in) { fibra::restoreCheckpoint(*s_, in); }

}  // namespace fibra
