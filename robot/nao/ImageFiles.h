#pragma once
// The image files of a folder as --cameras files:DIR takes them (header-only: the command
// line's declarations check the folder with it, and the argv fuzzer links nothing of robot/).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace nao {

// The PNG and JPEG files (.png, .jpg, .jpeg, any case) directly in `dir`, in name order; empty
// when there are none or `dir` is no folder.
inline std::vector<std::string> imageFilesIn(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    std::string ext = it->path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace nao
