#include "apps/Cli.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "robot/Error.h"
#include "robot/OutputFiles.h"

namespace nao::cli {

void writeJson(const std::string& target, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  if (target != "-") {
    io::writeFile(target, text);
    return;
  }
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
    throw RunFailure("stdout", "write failed");
}

DebugSink::DebugSink(const DebugOptions& options) {
  if (options.channels.empty()) return;
  if (!options.out.empty()) {
    file_.open(options.out, std::ios::out | std::ios::trunc);
    if (!file_) throw RunFailure(options.out, "cannot be written");
  }
  channels_ = std::make_unique<DebugChannels>(options.out.empty() ? static_cast<std::ostream&>(std::cerr) : file_);
  channels_->subscribe(options.channels);
}

void progress(const std::string& what, std::size_t done, std::size_t total) {
  static const bool tty = isatty(fileno(stderr));
  if (tty) {
    std::fprintf(stderr, "\r%s %zu/%zu", what.c_str(), done, total);
    if (done == total) std::fputc('\n', stderr);
  } else if (done == total || total < 20 || done % (total / 10) == 0) {
    std::fprintf(stderr, "%s %zu/%zu\n", what.c_str(), done, total);
  }
}

}  // namespace nao::cli
