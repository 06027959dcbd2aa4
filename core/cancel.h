// Cancellation of long work. The embedder's cancel callback (WorldDef::cancel) is polled only on
// the thread that owns it, the one that called World::step, so the callback is never invoked
// concurrently; once it says stop, the request is latched and every worker sees it. Long
// systems (detection on large assemblies) check it once per chunk of work and return early,
// leaving their output incomplete; the driver then discards the attempt.
#pragma once

#include <atomic>
#include <functional>
#include <thread>

namespace fibra {

class Cancel {
 public:
  // From now on, `poll` is asked on the calling thread (none: never cancelled).
  void arm(std::function<bool()> poll) {
    poll_ = std::move(poll);
    owner_ = std::this_thread::get_id();
    latched_.store(false, std::memory_order_relaxed);
  }
  // True once cancellation was asked; polls the callback when called on the owning thread.
  bool operator()() const {
    if (latched_.load(std::memory_order_relaxed)) return true;
    if (poll_ && std::this_thread::get_id() == owner_ && poll_())
      latched_.store(true, std::memory_order_relaxed);
    return latched_.load(std::memory_order_relaxed);
  }
  // True once cancellation was asked, without polling.
  bool requested() const { return latched_.load(std::memory_order_relaxed); }

 private:
  std::function<bool()> poll_;
  std::thread::id owner_;
  mutable std::atomic<bool> latched_{false};
};

}  // namespace fibra
