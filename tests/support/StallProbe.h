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

// The machine's own stalls. On each CPU the process may use, a thread at SCHED_FIFO 30 (above
// the peer and the program), pinned there, wakes every 5 ms and records each wake-up more than
// 2 ms late (waking every 2 ms on both CPUs made the program itself late now and then). On a
// shared virtual machine even an idle real-time thread is now and then woken 10-27 ms late (the
// host runs something else on that virtual CPU: on this project's machines about twice a
// minute, with nothing else running); a late answer during such a stall is the machine's, not
// the program's. One probe per CPU, because a stall of the CPU the program or the peer ran on
// is invisible to a probe on the other one (a CI run saw an 18 ms answer with the program's own
// turnaround at 3 ms and a single probe awake throughout). Without the right to real-time
// priority (not root) the probes still run, at normal priority.
class StallProbe {
 public:
  StallProbe() {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    std::vector<int> cpus;
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0)
      for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &allowed)) cpus.push_back(cpu);
    if (cpus.empty()) cpus.push_back(-1);  // unknown: one unpinned probe
    for (const int cpu : cpus) threads_.emplace_back([this, cpu] { loop(cpu); });
  }
  ~StallProbe() {
    stop_ = true;
    for (auto& thread : threads_) thread.join();
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
    nlohmann::json intervals = nlohmann::json::array();  // [due, woke], monotonic s (as the program's times)
    for (const auto& [due, woke] : stalls_) {
      const double ms = (woke - due) * 1000;
      over5 += ms > 5;
      over12 += ms > 12;
      max = std::max(max, ms);
      intervals.push_back({due, woke});
    }
    return {{"over_2ms", stalls_.size()}, {"over_5ms", over5}, {"over_12ms", over12}, {"max_ms", max},
            {"real_time", realTime_.load()}, {"intervals", intervals}};
  }

 private:
  void loop(int cpu) {
    if (cpu >= 0) {
      cpu_set_t one;
      CPU_ZERO(&one);
      CPU_SET(cpu, &one);
      pthread_setaffinity_np(pthread_self(), sizeof one, &one);
    }
    sched_param rt{};
    rt.sched_priority = 30;
    const bool realTime = pthread_setschedparam(pthread_self(), SCHED_FIFO, &rt) == 0;
    if (!realTime) realTime_ = false;
    constexpr double kPeriod = 0.005;
    double due = monotonic();
    while (!stop_) {
      due += kPeriod;
      sleepUntil(due);
      const double woke = monotonic();
      if (woke - due > 0.002) {
        std::lock_guard<std::mutex> lock(mutex_);
        stalls_.emplace_back(due, woke);
      }
      if (woke - due > 0.05) due = woke;  // no burst after a long stall
    }
  }
  mutable std::mutex mutex_;
  std::vector<std::pair<double, double>> stalls_;
  std::atomic<bool> stop_{false}, realTime_{true};
  std::vector<std::thread> threads_;
};

}  // namespace lola_wire
