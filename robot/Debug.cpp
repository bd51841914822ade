#include "robot/Debug.h"

#include <map>
#include <stdexcept>

#include "robot/Error.h"

namespace nao {

namespace {

// A function-local static: channels register during static initialisation, in any order.
std::map<std::string, const DebugChannel*>& registry() {
  static std::map<std::string, const DebugChannel*> r;
  return r;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    names.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return names;
    start = comma + 1;
  }
}

bool validName(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

}  // namespace

DebugChannel::DebugChannel(const char* name, const char* description) : name_(name), description_(description) {
  auto& r = registry();
  if (!validName(name)) throw std::logic_error(std::string("debug channel name '") + name + "' is not [a-z0-9_]+");
  if (r.size() >= 64) throw std::logic_error(std::string("debug channel ") + name + ": more than 64 channels");
  if (!r.emplace(name, this).second) throw std::logic_error(std::string("debug channel ") + name + " declared twice");
  bit_ = std::uint64_t{1} << (r.size() - 1);
}

std::vector<DebugChannelInfo> debugChannelList() {
  std::vector<DebugChannelInfo> list;
  for (const auto& [name, c] : registry()) list.push_back({name, c->description()});
  return list;
}

std::string debugChannelsProblem(const std::string& list) {
  for (const std::string& name : split(list)) {
    if (registry().count(name)) continue;
    std::string known;
    for (const auto& [n, c] : registry()) known += (known.empty() ? "" : ", ") + n;
    const std::string what = name.empty() ? std::string("an empty channel name") : "unknown channel '" + name + "'";
    return what + " (channels: " + (known.empty() ? "none" : known) + ")";
  }
  return "";
}

void DebugChannels::subscribe(const std::string& list, const std::string& where) {
  if (const std::string problem = debugChannelsProblem(list); !problem.empty()) throw Error(where, problem);
  for (const std::string& name : split(list)) mask_ |= registry().at(name)->bit();
}

namespace {
thread_local double t_debugTime = 0;  // DebugChannels::setTime's, per thread
}  // namespace

void DebugChannels::setTime(double t) { t_debugTime = t; }
double DebugChannels::time() const { return t_debugTime; }

void DebugChannels::write(const DebugChannel& channel, const nlohmann::json& payload) {
  // Built by hand so that "channel" and "t" lead the line (nlohmann::json sorts its keys).
  std::string line = "{\"channel\":\"";
  line += channel.name();
  line += "\",\"t\":";
  line += nlohmann::json(t_debugTime).dump();
  if (payload.is_object()) {
    for (const auto& [key, value] : payload.items())
      if (key != "channel" && key != "t") {
        line += ',';
        line += nlohmann::json(key).dump();
        line += ':';
        line += value.dump();
      }
  } else if (!payload.is_null()) {
    line += ",\"value\":";
    line += payload.dump();
  }
  line += "}\n";
  std::lock_guard<std::mutex> lock(mutex_);
  ++lines_;
  if (sink_) {
    sink_->write(line.data(), static_cast<std::streamsize>(line.size()));
    sink_->flush();  // a crash or a kill keeps what was written
  }
}

DebugChannels& DebugChannels::none() {
  static DebugChannels n;
  return n;
}

}  // namespace nao
