#pragma once
// Where models/ and config/ live: $NAO_SOCCER_HOME if set (a deployed robot), else the
// source tree the binary was built from.
#include <cstdlib>
#include <string>

namespace nao {

inline std::string dataRoot() {
  if (const char* home = std::getenv("NAO_SOCCER_HOME"); home && *home) return home;
  return NAO_SOURCE_DIR;
}
inline std::string dataPath(const std::string& relative) { return dataRoot() + "/" + relative; }

}  // namespace nao
