// Task graph: runs a set of systems as a oneTBB flow graph whose edges come from what each
// system declares it reads and writes (as in EnTT's organizer), never from hand-counted
// dependencies.
//
//   TaskGraph g;
//   g.add("beam assembly", reads(fibres, beams), writes(system), [&] { ... });
//   g.build();          // once per configuration
//   g.run(trace);       // once per iteration, in the caller's task arena
//
// Edge rule, in insertion order: a system runs after the last writer of every store it reads or
// writes (read-after-write, write-after-write) and after every reader of a store it writes since
// that store's last write (write-after-read). Systems with no conflicts run concurrently. A store
// is identified by its address. Each system runs inside a Span named after it.
#pragma once

#include "core/trace.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fibra {

using Access = std::vector<const void*>;

template <class... T>
Access reads(const T&... stores) {
  return {static_cast<const void*>(&stores)...};
}
template <class... T>
Access writes(const T&... stores) {
  return {static_cast<const void*>(&stores)...};
}

class TaskGraph {
 public:
  TaskGraph();
  ~TaskGraph();
  TaskGraph(const TaskGraph&) = delete;
  TaskGraph& operator=(const TaskGraph&) = delete;

  // `name` must outlive the graph (a string literal).
  void add(const char* name, Access reads, Access writes, std::function<void()> run);
  void build();
  void run(Trace* trace);
  void clear();

  // Predecessors of system i (indices in insertion order), for tests and documentation.
  const std::vector<int>& predecessors(int i) const;
  int size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fibra
