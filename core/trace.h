// Profiling trace: named spans of wall time, recorded from any thread, written as a Chrome
// trace-event JSON (open it in Perfetto or chrome://tracing) and as a per-stage CSV.
//
// A Trace belongs to whoever creates it (the command-line program for `--trace FILE`, a bench,
// an embedding program) and is handed to a World through WorldDef::trace; there is no global
// profiler. Recording is thread-safe and lock-free on the hot path (per-thread buffers). A null
// Trace* makes every Span a no-op.
//
//   fibra::Span span(trace, "broadphase");   // records on destruction
//   span.items(pairs.size());                // optional: work items, for throughput
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fibra {

class Trace {
 public:
  using Clock = std::chrono::steady_clock;

  struct Event {
    const char* name;      // static string
    const char* category;  // static string
    Clock::time_point begin, end;
    std::int64_t items;    // work items processed, -1 if not counted
    int thread;            // small integer id of the recording thread
  };

  Trace();
  ~Trace();
  Trace(const Trace&) = delete;
  Trace& operator=(const Trace&) = delete;

  void record(const char* name, const char* category, Clock::time_point begin,
              Clock::time_point end, std::int64_t items = -1);
  std::vector<Event> events() const;  // all events, sorted by begin time
  void clear();

  // Chrome trace-event format ("X" complete events, microseconds since the trace's creation).
  void writeChromeJson(const std::string& path) const;
  // One row per span name: calls, total/mean/min/max milliseconds, items, items per second.
  void writeStageCsv(const std::string& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class Span {
 public:
  Span(Trace* trace, const char* name, const char* category = "system")
      : trace_(trace), name_(name), category_(category) {
    if (trace_) begin_ = Trace::Clock::now();
  }
  ~Span() {
    if (trace_) trace_->record(name_, category_, begin_, Trace::Clock::now(), items_);
  }
  Span(const Span&) = delete;
  Span& operator=(const Span&) = delete;
  void items(std::int64_t n) { items_ = n; }

 private:
  Trace* trace_;
  const char* name_;
  const char* category_;
  Trace::Clock::time_point begin_{};
  std::int64_t items_ = -1;
};

}  // namespace fibra
