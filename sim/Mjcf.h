#pragma once
// Small helpers for writing MJCF with tinyxml2 (the scene builder's and the venue's).
#include <tinyxml2.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>

namespace nao::sim::mjcf {

// A number as MJCF text (9 significant digits; -0 and tiny values as 0).
inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}
inline std::string vec(std::initializer_list<double> values) {
  std::string s;
  for (double v : values) {
    if (!s.empty()) s += ' ';
    s += num(v);
  }
  return s;
}
// Rotation about z by angle a as an MJCF quat (independent of the compiler's angle unit).
inline std::string yawQuat(double a) { return vec({std::cos(a / 2), 0, 0, std::sin(a / 2)}); }

inline tinyxml2::XMLElement* add(tinyxml2::XMLNode* parent, const char* tag) {
  tinyxml2::XMLElement* e = parent->GetDocument()->NewElement(tag);
  parent->InsertEndChild(e);
  return e;
}
inline tinyxml2::XMLElement* add(tinyxml2::XMLNode* parent, const char* tag,
                                 std::initializer_list<std::pair<const char*, std::string>> attributes) {
  tinyxml2::XMLElement* e = add(parent, tag);
  for (const auto& [key, value] : attributes) e->SetAttribute(key, value.c_str());
  return e;
}

}  // namespace nao::sim::mjcf
