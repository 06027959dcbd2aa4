#include "core/table.h"

#include <algorithm>

namespace fibra {

double tableValue(const Table& table, double t) {
  if (table.t.empty()) return 0;
  if (t <= table.t.front()) return table.v.front();
  if (t >= table.t.back()) return table.v.back();
  const size_t i = size_t(std::upper_bound(table.t.begin(), table.t.end(), t) - table.t.begin());
  const double u = (t - table.t[i - 1]) / (table.t[i] - table.t[i - 1]);
  return table.v[i - 1] + u * (table.v[i] - table.v[i - 1]);
}

}  // namespace fibra
