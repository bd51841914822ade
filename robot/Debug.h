#pragma once
// Debug channels: named streams of JSON lines, filled only while subscribed (`--debug
// CHANNEL[,CHANNEL]`, docs/architecture.md "Debug channels"). Each channel is declared once,
// at namespace scope next to the code that fills it, with a one-line description:
//
//   NAO_DEBUG_CHANNEL(kWalkTrace, "walk_trace", "the walk's swing target at mid-step ...");
//   ...
//   if (debug_->on(kWalkTrace)) debug_->write(kWalkTrace, {{"support", "left"}, ...});
//   debug_->emit(kWalkTrace, [&] { return nlohmann::json{...}; });   // the same, as a lambda
//
// An unsubscribed channel costs one test of a bit: no JSON is built. A subscribed one writes
// {"channel": NAME, "t": TIME, ...the payload's keys} as one line to the sink, where TIME is
// the backend's clock of the cycle or image being processed (setTime).
#include <cstdint>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nao {

// A declared channel. Registered when constructed (static initialisation); a name declared
// twice, a name that is not [a-z0-9_]+, or more than 64 channels throw std::logic_error.
class DebugChannel {
 public:
  DebugChannel(const char* name, const char* description);
  DebugChannel(const DebugChannel&) = delete;
  DebugChannel& operator=(const DebugChannel&) = delete;
  const char* name() const { return name_; }
  const char* description() const { return description_; }
  std::uint64_t bit() const { return bit_; }

 private:
  const char* name_;
  const char* description_;
  std::uint64_t bit_;
};

struct DebugChannelInfo {
  std::string name, description;
};
// Every declared channel of this program, by name.
std::vector<DebugChannelInfo> debugChannelList();
// Why `list` ("a,b") is no list of declared channels ("" if it is): an empty name or an unknown
// one, with the known names.
std::string debugChannelsProblem(const std::string& list);

class DebugChannels {
 public:
  DebugChannels() = default;  // nothing subscribed, no sink
  explicit DebugChannels(std::ostream& sink) : sink_(&sink) {}
  DebugChannels(const DebugChannels&) = delete;
  DebugChannels& operator=(const DebugChannels&) = delete;

  // Subscribes each channel of "a,b". Throws nao::Error(where, debugChannelsProblem) for an
  // unknown one, subscribing none of them.
  void subscribe(const std::string& list, const std::string& where = "--debug");
  bool on(const DebugChannel& channel) const { return (mask_ & channel.bit()) != 0; }
  bool any() const { return mask_ != 0; }

  // The time lines carry: the backend's clock (s) of the cycle or image the calling thread is
  // processing. Kept per thread: on a NAO motion and cognition write from threads of their own.
  void setTime(double t);
  double time() const;

  // Writes one line if `channel` is subscribed; `payload()` (returning nlohmann::json, an
  // object whose keys join "channel" and "t", or any other value as "value") runs only then.
  template <class F>
  void emit(const DebugChannel& channel, F&& payload) {
    if (on(channel)) write(channel, payload());
  }
  // Writes one line unconditionally (callers test on() first); safe from several threads.
  void write(const DebugChannel& channel, const nlohmann::json& payload);
  long linesWritten() const { return lines_; }

  // A shared, never subscribed instance: what holders of a DebugChannels* point to by default,
  // so that their test stays one branch. Never written.
  static DebugChannels& none();

 private:
  std::ostream* sink_ = nullptr;
  std::uint64_t mask_ = 0;
  long lines_ = 0;
  std::mutex mutex_;
};

}  // namespace nao

// At namespace scope in the .cpp that fills the channel: a DebugChannel named `var`.
#define NAO_DEBUG_CHANNEL(var, name, description) static const ::nao::DebugChannel var{name, description}
