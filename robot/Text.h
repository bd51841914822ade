#pragma once
// Text from a file or the command line inside a one-line error message: control characters
// written as escapes (\n, \r, \t, \xNN), so the message stays one line.
#include <cstdio>
#include <string>

namespace nao {

inline std::string escapeControl(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

}  // namespace nao
