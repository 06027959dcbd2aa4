// A piecewise-linear function of pseudo-time, the shape of every prescribed motion and load.
#pragma once

#include <vector>

namespace fibra {

// value(t) interpolates the points (t_i, v_i), t strictly increasing, and is constant beyond
// the first and last points.
struct Table {
  std::vector<double> t;  // pseudo-time
  std::vector<double> v;  // value (unit of what it scales)
};

// value of a table at pseudo-time t (constant beyond its ends; 0 for an empty table).
double tableValue(const Table& table, double t);

}  // namespace fibra
