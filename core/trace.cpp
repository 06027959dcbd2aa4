#include "core/trace.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <iomanip>
#include <map>
#include <stdexcept>

namespace fibra {

struct Trace::Impl {
  struct Local {
    int thread = -1;
    std::vector<Event> events;
  };
  Clock::time_point origin = Clock::now();
  std::atomic<int> nextThread{0};
  tbb::enumerable_thread_specific<Local> locals;
};

Trace::Trace() : impl_(std::make_unique<Impl>()) {}
Trace::~Trace() = default;

void Trace::record(const char* name, const char* category, Clock::time_point begin,
                   Clock::time_point end, std::int64_t items) {
  Impl::Local& local = impl_->locals.local();
  if (local.thread < 0) local.thread = impl_->nextThread++;
  local.events.push_back({name, category, begin, end, items, local.thread});
}

std::vector<Trace::Event> Trace::events() const {
  std::vector<Event> all;
  for (const Impl::Local& l : impl_->locals) all.insert(all.end(), l.events.begin(), l.events.end());
  std::sort(all.begin(), all.end(), [](const Event& a, const Event& b) {
    return a.begin < b.begin || (a.begin == b.begin && a.thread < b.thread);
  });
  return all;
}

void Trace::clear() {
  for (Impl::Local& l : impl_->locals) l.events.clear();
}

namespace {

double micros(Trace::Clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

std::ofstream openOrThrow(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write trace file " + path);
  return out;
}

}  // namespace

void Trace::writeChromeJson(const std::string& path) const {
  std::ofstream out = openOrThrow(path);
  // Microseconds with three decimals: the clock's nanoseconds, whatever the run's length.
  out << std::fixed << std::setprecision(3);
  out << "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
  bool first = true;
  for (const Event& e : events()) {
    out << (first ? "" : ",\n") << "{\"name\":\"" << e.name << "\",\"cat\":\"" << e.category
        << "\",\"ph\":\"X\",\"pid\":1,\"tid\":" << e.thread
        << ",\"ts\":" << micros(e.begin - impl_->origin) << ",\"dur\":" << micros(e.end - e.begin);
    if (e.items >= 0) out << ",\"args\":{\"items\":" << e.items << "}";
    out << "}";
    first = false;
  }
  out << "\n]}\n";
}

void Trace::writeStageCsv(const std::string& path) const {
  struct Stage {
    long calls = 0;
    double total = 0, min = 1e300, max = 0;
    std::int64_t items = 0;
  };
  std::map<std::string, Stage> stages;
  for (const Event& e : events()) {
    Stage& s = stages[e.name];
    const double ms = micros(e.end - e.begin) / 1000;
    ++s.calls;
    s.total += ms;
    s.min = std::min(s.min, ms);
    s.max = std::max(s.max, ms);
    if (e.items > 0) s.items += e.items;
  }
  std::ofstream out = openOrThrow(path);
  out << "stage,calls,total_ms,mean_ms,min_ms,max_ms,items,items_per_s\n";
  for (const auto& [name, s] : stages) {
    out << name << ',' << s.calls << ',' << s.total << ',' << s.total / s.calls << ',' << s.min
        << ',' << s.max << ',' << s.items << ','
        << (s.items > 0 && s.total > 0 ? s.items / (s.total / 1000) : 0) << '\n';
  }
}

}  // namespace fibra
