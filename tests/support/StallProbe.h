#pragma once
// The machine's own stalls, for judging answer times on a shared virtual machine.
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/LolaWire.h"

namespace lola_wire {

// The machine's own stalls. A thread at SCHED_FIFO 30 (above the peer and the program) wakes
// every 2 ms and records each wake-up more than 2 ms late. On a shared virtual machine even an
// idle real-time thread is now and then woken 10-17 ms late (the host runs something else: on
// this project's machines about twice a minute, with nothing else running); a late answer
// during such a stall is the machine's, not the program's. Without the right to real-time
// priority (not root) the probe still runs, at normal priority.
class StallProbe {
 public:
  StallProbe() : thread_([this] { loop(); }) {}
  ~StallProbe() {
    stop_ = true;
    thread_.join();
  }
  // Whether the probe was held up during any part of [from, to] (monotonic seconds).
  bool stalledDuring(double from, double to) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [due, woke] : stalls_)
      if (due < to && woke > from) return true;
    return false;
  }
  nlohmann::json figures() const {
    std::lock_guard<std::mutex> lock(mutex_);
    int over5 = 0, over12 = 0;
    double max = 0;
    for (const auto& [due, woke] : stalls_) {
      const double ms = (woke - due) * 1000;
      over5 += ms > 5;
      over12 += ms > 12;
      max = std::max(max, ms);
    }
    return {{"over_2ms", stalls_.size()}, {"over_5ms", over5}, {"over_12ms", over12}, {"max_ms", max},
            {"real_time", realTime_.load()}};
  }

 private:
  void loop() {
    sched_param rt{};
    rt.sched_priority = 30;
    realTime_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &rt) == 0;
    constexpr double kPeriod = 0.002;
    double due = monotonic();
    while (!stop_) {
      due += kPeriod;
      sleepUntil(due);
      const double woke = monotonic();
      if (woke - due > kPeriod) {
        std::lock_guard<std::mutex> lock(mutex_);
        stalls_.emplace_back(due, woke);
      }
      if (woke - due > 0.05) due = woke;  // no burst after a long stall
    }
  }
  mutable std::mutex mutex_;
  std::vector<std::pair<double, double>> stalls_;
  std::atomic<bool> stop_{false}, realTime_{false};
  std::thread thread_;
};

}  // namespace lola_wire
