#include "robot/InputFiles.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "robot/Error.h"

namespace nao {

std::string readInputFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path, "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path, "cannot read file");
  return text.str();
}

}  // namespace nao
