#include "engine/task_graph.h"

#include <tbb/flow_graph.h>

#include <algorithm>

namespace fibra {

namespace flow = tbb::flow;

std::string StoreNames::of(const void* address) const {
  const auto it = names_.find(address);
  return it == names_.end() ? std::string() : it->second;
}

const void* StoreNames::whole(const void* address) const {
  const auto it = whole_.find(address);
  return it == whole_.end() ? address : it->second;
}

struct TaskGraph::Impl {
  struct System {
    const char* name;
    Access reads, writes;
    std::function<void()> run;
    std::vector<int> predecessors;
  };
  const StoreNames* names = nullptr;
  std::vector<System> systems;
  Trace* trace = nullptr;
  std::unique_ptr<flow::graph> graph;
  std::unique_ptr<flow::broadcast_node<flow::continue_msg>> start;
  std::vector<std::unique_ptr<flow::continue_node<flow::continue_msg>>> nodes;
};

TaskGraph::TaskGraph(const StoreNames* names) : impl_(std::make_unique<Impl>()) {
  impl_->names = names;
}
TaskGraph::~TaskGraph() = default;

void TaskGraph::checkNamed(const char* system, const void* store, const char* type) const {
  if (impl_->names && impl_->names->of(store).empty())
    throw std::logic_error(std::string("task graph: system '") + system +
                           "' is bound to an unnamed store of type " + type);
}

void TaskGraph::addSystem(const char* name, Access r, Access w, std::function<void()> run) {
  impl_->systems.push_back({name, std::move(r), std::move(w), std::move(run), {}});
}

void TaskGraph::build() {
  Impl& m = *impl_;
  const auto whole = [&m](const void* store) { return m.names ? m.names->whole(store) : store; };
  std::map<const void*, int> lastWriter;
  std::map<const void*, std::vector<int>> readersSinceWrite;
  for (int i = 0; i < int(m.systems.size()); ++i) {
    Impl::System& s = m.systems[i];
    std::vector<int>& pred = s.predecessors;
    pred.clear();
    for (const void* part : s.reads)
      if (auto it = lastWriter.find(whole(part)); it != lastWriter.end()) pred.push_back(it->second);
    for (const void* part : s.writes) {
      const void* store = whole(part);
      if (auto it = lastWriter.find(store); it != lastWriter.end()) pred.push_back(it->second);
      for (int r : readersSinceWrite[store]) pred.push_back(r);
    }
    std::sort(pred.begin(), pred.end());
    pred.erase(std::unique(pred.begin(), pred.end()), pred.end());
    pred.erase(std::remove(pred.begin(), pred.end(), i), pred.end());
    for (const void* part : s.reads) readersSinceWrite[whole(part)].push_back(i);
    for (const void* part : s.writes) {
      lastWriter[whole(part)] = i;
      readersSinceWrite[whole(part)].clear();
    }
  }

  m.graph = std::make_unique<flow::graph>();
  m.start = std::make_unique<flow::broadcast_node<flow::continue_msg>>(*m.graph);
  m.nodes.clear();
  for (Impl::System& s : m.systems) {
    Impl::System* sys = &s;
    m.nodes.push_back(std::make_unique<flow::continue_node<flow::continue_msg>>(
        *m.graph, [sys, &m](const flow::continue_msg&) {
          Span span(m.trace, sys->name);
          sys->run();
        }));
  }
  for (int i = 0; i < int(m.systems.size()); ++i) {
    if (m.systems[i].predecessors.empty()) flow::make_edge(*m.start, *m.nodes[i]);
    for (int p : m.systems[i].predecessors) flow::make_edge(*m.nodes[p], *m.nodes[i]);
  }
}

void TaskGraph::run(Trace* trace) {
  if (impl_->systems.empty()) return;
  impl_->trace = trace;
  impl_->start->try_put(flow::continue_msg());
  impl_->graph->wait_for_all();
}

void TaskGraph::clear() {
  impl_->nodes.clear();
  impl_->start.reset();
  impl_->graph.reset();
  impl_->systems.clear();
}

int TaskGraph::size() const { return int(impl_->systems.size()); }
const char* TaskGraph::name(int i) const { return impl_->systems[i].name; }

int TaskGraph::find(const std::string& name) const {
  for (int i = 0; i < size(); ++i)
    if (name == impl_->systems[i].name) return i;
  return -1;
}

const std::vector<int>& TaskGraph::predecessors(int i) const { return impl_->systems[i].predecessors; }

bool TaskGraph::ordered(int a, int b) const {
  // Predecessors have smaller indices: search backwards from the later one.
  const int from = std::max(a, b), to = std::min(a, b);
  std::vector<bool> seen(size(), false);
  std::vector<int> stack{from};
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    if (i == to) return true;
    for (int p : predecessors(i))
      if (p >= to && !seen[p]) seen[p] = true, stack.push_back(p);
  }
  return false;
}

namespace {

std::vector<std::string> namesOf(const StoreNames* names, const Access& stores) {
  std::vector<std::string> out;
  for (const void* s : stores) out.push_back(names ? names->of(s) : std::string());
  return out;
}

}  // namespace

std::vector<std::string> TaskGraph::reads(int i) const {
  return namesOf(impl_->names, impl_->systems[i].reads);
}
std::vector<std::string> TaskGraph::writes(int i) const {
  return namesOf(impl_->names, impl_->systems[i].writes);
}

}  // namespace fibra
