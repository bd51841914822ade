#pragma once
// Reading a whole input file (a config, a parameter or camera-matrix file) with errors a user
// can act on: nao::Error(path, "file not found" | "not a regular file" | "cannot open file" |
// "cannot read file").
#include <string>

namespace nao {

std::string readInputFile(const std::string& path);

}  // namespace nao
