// Task graph: runs a set of systems as a oneTBB flow graph whose edges follow from what each
// system reads and writes — and those sets are derived from the system's signature, as EnTT's
// organizer does: a `const Store&` parameter reads that store, a `Store&` parameter writes it,
// a pointer parameter (Trace*) is passed through. Nothing is declared beside the code.
//
//   StoreNames names;
//   names.add(w.fibres, "fibres");  ...            // every bound store has a name
//   TaskGraph g(&names);
//   g.add("beam evaluation", evaluateBeams, w.fibres, w.beams, w.input, w.beamForces);
//   g.build();          // once per configuration
//   g.run(trace);       // once per iteration, in the caller's task arena
//
// Edge rule, in insertion order: a system runs after the last writer of every store it reads or
// writes (read-after-write, write-after-write) and after every reader of a store it writes since
// that store's last write (write-after-read). Systems with no path between them run side by
// side. A store is identified by its address; a named part of a store (StoreNames::addPart)
// by the whole's. A system may read what it writes (a write is a read-modify-write). Each
// system runs inside a Span named after it.
#pragma once

#include "core/trace.h"

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <vector>

namespace fibra {

using Access = std::vector<const void*>;

// Names of the stores the systems of a world are bound to, for the graph's description (the
// docs, the tests) and its errors.
class StoreNames {
 public:
  template <class T>
  void add(const T& store, std::string name) {
    names_[static_cast<const void*>(&store)] = std::move(name);
  }
  // A named part of a store (a column a system takes on its own, like fibres.q): edges treat
  // an access to the part as an access to the whole.
  template <class P, class T>
  void addPart(const P& part, std::string name, const T& whole) {
    add(part, std::move(name));
    whole_[static_cast<const void*>(&part)] = static_cast<const void*>(&whole);
  }
  // The name of the store at `address`, or "" when it has none.
  std::string of(const void* address) const;
  // The store that `address` is part of (itself when it is a whole store).
  const void* whole(const void* address) const;

 private:
  std::map<const void*, std::string> names_;
  std::map<const void*, const void*> whole_;
};

class TaskGraph {
 public:
  explicit TaskGraph(const StoreNames* names = nullptr);
  ~TaskGraph();
  TaskGraph(const TaskGraph&) = delete;
  TaskGraph& operator=(const TaskGraph&) = delete;

  // Adds `system` bound to `args` (lvalues that outlive the graph), one per parameter: stores for
  // reference parameters, pointers for pointer parameters. `name` must outlive the graph (a
  // string literal). Throws std::logic_error when a bound store has no name in `names`.
  template <class R, class... P, class... A>
  void add(const char* name, R (*system)(P...), A&... args) {
    static_assert(sizeof...(P) == sizeof...(A), "bind one argument per parameter");
    Access reads, writes;
    (classify<P, A>(name, args, reads, writes), ...);
    addSystem(name, std::move(reads), std::move(writes), [system, &args...] { system(args...); });
  }

  void build();
  void run(Trace* trace);
  void clear();

  // --- introspection (tests, docs/ARCHITECTURE.md) ---
  int size() const;
  const char* name(int i) const;
  int find(const std::string& name) const;              // -1 when absent
  const std::vector<int>& predecessors(int i) const;    // indices in insertion order
  bool ordered(int a, int b) const;                     // a path from a to b or from b to a
  std::vector<std::string> reads(int i) const;          // store names
  std::vector<std::string> writes(int i) const;

 private:
  template <class P, class A>
  void classify(const char* system, A& arg, Access& reads, Access& writes) {
    if constexpr (std::is_pointer_v<P>) {
      static_assert(std::is_same_v<std::remove_const_t<P>, std::remove_const_t<A>>,
                    "a pointer parameter takes a pointer of its type");
    } else {
      static_assert(std::is_lvalue_reference_v<P>, "a system takes its stores by reference");
      using Store = std::remove_reference_t<P>;
      static_assert(std::is_same_v<std::remove_const_t<Store>, std::remove_const_t<A>>,
                    "a store parameter is bound to a store of its own type");
      static_assert(std::is_const_v<Store> || !std::is_const_v<A>,
                    "a store a system writes is bound to a mutable store");
      checkNamed(system, &arg, typeid(Store).name());
      (std::is_const_v<Store> ? reads : writes).push_back(static_cast<const void*>(&arg));
    }
  }
  void checkNamed(const char* system, const void* store, const char* type) const;
  void addSystem(const char* name, Access reads, Access writes, std::function<void()> run);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fibra
