// Groups in resolution order: Kahn's algorithm over "union names scene group" edges, then, when
// unions are left, the cycle they hold, found by following unresolved members.
#include "engine/group_order.h"

#include "core/errors.h"

#include <cstdint>
#include <deque>
#include <map>
#include <string>

namespace fibra {
namespace {

// Per group, the scene groups its members name: (the member's group index, k in union[k]).
using Edges = std::vector<std::vector<std::pair<size_t, size_t>>>;

Edges memberGroups(const std::vector<GroupDef>& groups) {
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < groups.size(); ++i) index.emplace(groups[i].name, i);
  Edges edges(groups.size());
  for (size_t i = 0; i < groups.size(); ++i)
    for (size_t k = 0; k < groups[i].members.size(); ++k)
      if (const auto m = index.find(groups[i].members[k]); m != index.end())
        edges[i].emplace_back(m->second, k);
  return edges;
}

// A cycle among the unresolved unions (each has an unresolved member), found by following
// unresolved members from the first unresolved group; reported at the cycle's group listed first.
[[noreturn]] void cycleError(const std::vector<GroupDef>& groups, const Edges& edges,
                             const std::vector<bool>& done) {
  size_t g = 0;
  while (done[g]) ++g;
  std::vector<size_t> position(groups.size(), SIZE_MAX);  // on the walk
  std::vector<std::pair<size_t, size_t>> walk;            // (group, k of the member followed)
  while (position[g] == SIZE_MAX) {
    position[g] = walk.size();
    for (const auto& [m, k] : edges[g])
      if (!done[m]) {
        walk.emplace_back(g, k);
        g = m;
        break;
      }
  }
  const size_t first = position[g], length = walk.size() - first;
  size_t lead = first;
  for (size_t p = first; p < walk.size(); ++p)
    if (walk[p].first < walk[lead].first) lead = p;
  std::string chain;
  for (size_t p = 0; p <= length; ++p)
    chain += (p ? " -> " : "") + groups[walk[first + (lead - first + p) % length].first].name;
  const auto [i, k] = walk[lead];
  const std::string path = "groups[" + std::to_string(i) + "].union[" + std::to_string(k) + "]";
  if (length == 1) throw SceneError(path + ": a group cannot be a union of itself");
  throw SceneError(path + ": group '" + groups[i].members[k] +
                   "' includes this group through its own union (a cycle: " + chain + ")");
}

}  // namespace

std::vector<size_t> groupResolutionOrder(const std::vector<GroupDef>& groups) {
  const Edges edges = memberGroups(groups);
  std::vector<size_t> waiting(groups.size(), 0);  // members not resolved yet
  std::vector<std::vector<size_t>> users(groups.size());
  for (size_t i = 0; i < groups.size(); ++i)
    for (const auto& [m, k] : edges[i]) {
      ++waiting[i];
      users[m].push_back(i);
    }
  std::deque<size_t> ready;
  for (size_t i = 0; i < groups.size(); ++i)
    if (waiting[i] == 0) ready.push_back(i);
  std::vector<size_t> order;
  std::vector<bool> done(groups.size(), false);
  while (!ready.empty()) {
    const size_t g = ready.front();
    ready.pop_front();
    order.push_back(g);
    done[g] = true;
    for (size_t u : users[g])
      if (--waiting[u] == 0) ready.push_back(u);
  }
  if (order.size() < groups.size()) cycleError(groups, edges, done);
  return order;
}

}  // namespace fibra
