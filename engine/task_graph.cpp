#include "engine/task_graph.h"

#include <tbb/flow_graph.h>

#include <algorithm>
#include <map>

namespace fibra {

namespace flow = tbb::flow;

struct TaskGraph::Impl {
  struct System {
    const char* name;
    Access reads, writes;
    std::function<void()> run;
    std::vector<int> predecessors;
  };
  std::vector<System> systems;
  Trace* trace = nullptr;
  std::unique_ptr<flow::graph> graph;
  std::unique_ptr<flow::broadcast_node<flow::continue_msg>> start;
  std::vector<std::unique_ptr<flow::continue_node<flow::continue_msg>>> nodes;
};

TaskGraph::TaskGraph() : impl_(std::make_unique<Impl>()) {}
TaskGraph::~TaskGraph() = default;

void TaskGraph::add(const char* name, Access r, Access w, std::function<void()> run) {
  impl_->systems.push_back({name, std::move(r), std::move(w), std::move(run), {}});
}

void TaskGraph::build() {
  Impl& m = *impl_;
  std::map<const void*, int> lastWriter;
  std::map<const void*, std::vector<int>> readersSinceWrite;
  for (int i = 0; i < int(m.systems.size()); ++i) {
    Impl::System& s = m.systems[i];
    std::vector<int>& pred = s.predecessors;
    pred.clear();
    for (const void* store : s.reads)
      if (auto it = lastWriter.find(store); it != lastWriter.end()) pred.push_back(it->second);
    for (const void* store : s.writes) {
      if (auto it = lastWriter.find(store); it != lastWriter.end()) pred.push_back(it->second);
      for (int r : readersSinceWrite[store]) pred.push_back(r);
    }
    std::sort(pred.begin(), pred.end());
    pred.erase(std::unique(pred.begin(), pred.end()), pred.end());
    pred.erase(std::remove(pred.begin(), pred.end(), i), pred.end());
    for (const void* store : s.reads) readersSinceWrite[store].push_back(i);
    for (const void* store : s.writes) {
      lastWriter[store] = i;
      readersSinceWrite[store].clear();
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

const std::vector<int>& TaskGraph::predecessors(int i) const { return impl_->systems[i].predecessors; }
int TaskGraph::size() const { return int(impl_->systems.size()); }

}  // namespace fibra
