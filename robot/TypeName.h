#pragma once
// Readable C++ type names for messages and tables ("CameraMatrices", not a mangled typeid):
// taken from the compiler's own spelling of a template argument, so nothing has to be
// registered by hand. The namespaces nao:: and anonymous ones are left out.
#include <string>
#include <string_view>

namespace nao {
namespace detail {

template <class T>
constexpr std::string_view prettyFunction() {
  return __PRETTY_FUNCTION__;  // GCC: "... [with T = nao::X; ...]"; Clang: "... [T = nao::X]"
}

inline std::string cleanTypeName(std::string_view pretty) {
  const std::size_t at = pretty.find("T = ");
  if (at == std::string_view::npos) return std::string(pretty);
  std::string_view s = pretty.substr(at + 4);
  // The argument ends at the first ';' or ']' outside template brackets.
  int depth = 0;
  std::size_t end = 0;
  for (; end < s.size(); ++end) {
    const char c = s[end];
    if (c == '<' || c == '(' || c == '{') ++depth;
    else if (c == '>' || c == ')' || c == '}') --depth;
    else if (depth == 0 && (c == ';' || c == ']')) break;
  }
  std::string name(s.substr(0, end));
  for (const std::string_view drop : {"(anonymous namespace)::", "{anonymous}::", "nao::"})
    for (std::size_t p; (p = name.find(drop)) != std::string::npos;) name.erase(p, drop.size());
  return name;
}

}  // namespace detail

// "CameraMatrices", "modules::FallDetector", "std::vector<int>".
template <class T>
const std::string& typeName() {
  static const std::string name = detail::cleanTypeName(detail::prettyFunction<T>());
  return name;
}

// The name without any namespace or enclosing class: "FallDetector".
template <class T>
const std::string& shortTypeName() {
  static const std::string name = [] {
    const std::string& full = typeName<T>();
    int depth = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i < full.size(); ++i) {
      if (full[i] == '<') ++depth;
      else if (full[i] == '>') --depth;
      else if (depth == 0 && full[i] == ':' && i + 1 < full.size() && full[i + 1] == ':') start = i + 2;
    }
    return full.substr(start);
  }();
  return name;
}

}  // namespace nao
