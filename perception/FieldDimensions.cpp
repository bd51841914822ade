#include "perception/FieldDimensions.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "robot/InputFiles.h"

namespace nao {

namespace {

using nlohmann::json;

// "line L, column C" of a byte offset (nlohmann reports the offset just past the bad byte).
std::string lineColumn(const std::string& text, std::size_t byte) {
  byte = std::min(byte, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < byte; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message without its "[json.exception...] " prefix (and for a parse error its
// "parse error at line L, column C: " too), on one line.
std::string shortReason(const std::string& what, bool parseError) {
  std::string reason = what;
  if (auto pos = reason.find("] "); pos != std::string::npos) reason = reason.substr(pos + 2);
  if (auto pos = reason.find(": "); parseError && pos != std::string::npos) reason = reason.substr(pos + 2);
  for (char& c : reason)
    if (c == '\n' || c == '\r') c = ' ';
  return reason;
}

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

const json& section(const json& root, const char* name, const std::string& source) {
  auto it = root.find(name);
  if (it == root.end()) throw Error(source, std::string(name) + ": missing");
  if (!it->is_object()) throw Error(source, std::string(name) + ": must be an object");
  return *it;
}

double number(const json& sec, const char* sectionName, const char* key, const std::string& source) {
  const std::string name = std::string(sectionName) + "." + key;
  auto it = sec.find(key);
  if (it == sec.end()) throw Error(source, name + ": missing");
  if (!it->is_number()) throw Error(source, name + ": must be a number (got " + it->type_name() + ")");
  return it->get<double>();
}

}  // namespace

FieldDimensions FieldDimensions::load(const std::string& path) {
  return parse(readInputFile(path), path);
}

FieldDimensions FieldDimensions::parse(const std::string& jsonText, const std::string& sourceName) {
  json root;
  try {
    root = json::parse(jsonText);
  } catch (const json::parse_error& e) {
    throw Error(sourceName, "JSON syntax error at " + lineColumn(jsonText, e.byte) + ": " + shortReason(e.what(), true));
  } catch (const json::exception& e) {
    throw Error(sourceName, "invalid JSON: " + shortReason(e.what(), false));
  }
  if (!root.is_object()) throw Error(sourceName, "top level: must be an object");

  FieldDimensions d;
  const json& field = section(root, "field", sourceName);
  auto f = [&](const char* key) { return number(field, "field", key, sourceName); };

  d.length = f("length");
  d.width = f("width");
  d.penaltyCrossSize = f("penaltyCrossSize");
  const bool hasBoxLength = field.contains("goalBoxAreaLength");
  const bool hasBoxWidth = field.contains("goalBoxAreaWidth");
  if (hasBoxLength != hasBoxWidth)
    throw Error(sourceName, std::string(hasBoxLength ? "field.goalBoxAreaWidth" : "field.goalBoxAreaLength") +
                                ": missing (give both goalBoxArea keys or neither)");
  d.hasGoalBox = hasBoxLength;
  if (d.hasGoalBox) {
    d.goalBoxAreaLength = f("goalBoxAreaLength");
    d.goalBoxAreaWidth = f("goalBoxAreaWidth");
  }
  d.penaltyAreaLength = f("penaltyAreaLength");
  d.penaltyAreaWidth = f("penaltyAreaWidth");
  d.penaltyCrossDistance = f("penaltyCrossDistance");
  d.centerCircleDiameter = f("centerCircleDiameter");
  d.borderStripWidth = f("borderStripWidth");
  const json& goal = section(root, "goal", sourceName);
  auto g = [&](const char* key) { return number(goal, "goal", key, sourceName); };
  d.goalPostDiameter = g("postDiameter");
  d.goalHeight = g("height");
  d.goalInnerWidth = g("innerWidth");
  d.goalDepth = g("depth");
  d.validate(sourceName);
  return d;
}

void FieldDimensions::validate(const std::string& sourceName) const {
  auto positive = [&](const char* name, double v) {
    if (!std::isfinite(v)) throw Error(sourceName, std::string(name) + ": must be finite");
    if (v <= 0) throw Error(sourceName, std::string(name) + ": must be > 0 (got " + fmt(v) + ")");
  };
  positive("field.length", length);
  positive("field.width", width);
  positive("field.penaltyCrossSize", penaltyCrossSize);
  if (hasGoalBox) {
    positive("field.goalBoxAreaLength", goalBoxAreaLength);
    positive("field.goalBoxAreaWidth", goalBoxAreaWidth);
  }
  positive("field.penaltyAreaLength", penaltyAreaLength);
  positive("field.penaltyAreaWidth", penaltyAreaWidth);
  positive("field.penaltyCrossDistance", penaltyCrossDistance);
  positive("field.centerCircleDiameter", centerCircleDiameter);
  positive("field.borderStripWidth", borderStripWidth);
  positive("goal.postDiameter", goalPostDiameter);
  positive("goal.height", goalHeight);
  positive("goal.innerWidth", goalInnerWidth);
  positive("goal.depth", goalDepth);
  positive("lineWidth", lineWidth);
  // No SPL field comes near these; a value beyond them is a typo (metres for millimetres) that
  // would build a simulator world kilometres wide.
  auto atMost = [&](const char* name, double v, double max) {
    if (v > max) throw Error(sourceName, std::string(name) + ": " + fmt(v) + " m is implausible (at most " + fmt(max) + " m)");
  };
  atMost("field.length", length, 30);
  atMost("field.width", width, 20);
  atMost("field.borderStripWidth", borderStripWidth, 5);
  atMost("field.penaltyCrossSize", penaltyCrossSize, 1);
  atMost("goal.postDiameter", goalPostDiameter, 0.5);
  atMost("goal.height", goalHeight, 3);
  atMost("goal.depth", goalDepth, 3);
  atMost("lineWidth", lineWidth, 0.5);

  // name must be < limit (limitName = value)
  auto less = [&](const char* name, double v, const std::string& limitName, double limit) {
    if (!(v < limit))
      throw Error(sourceName, std::string(name) + ": " + fmt(v) + " must be < " + limitName + " (" + fmt(limit) + ")");
  };
  const double half = length / 2;
  less("field.penaltyAreaWidth", penaltyAreaWidth, "field.width", width);
  less("field.penaltyAreaLength", penaltyAreaLength, "half the field.length", half);
  less("field.centerCircleDiameter", centerCircleDiameter, "field.width", width);
  less("field.centerCircleDiameter", centerCircleDiameter / 2, "half the field.length - field.penaltyAreaLength",
       half - penaltyAreaLength);
  if (hasGoalBox) {
    less("field.goalBoxAreaLength", goalBoxAreaLength, "field.penaltyAreaLength", penaltyAreaLength);
    less("field.goalBoxAreaWidth", goalBoxAreaWidth, "field.penaltyAreaWidth", penaltyAreaWidth);
  }
  less("field.penaltyCrossDistance", penaltyCrossDistance + penaltyCrossSize / 2, "half the field.length", half);
  less("field.penaltyCrossSize", penaltyCrossSize, "field.penaltyCrossDistance", penaltyCrossDistance);
  less("goal.innerWidth", goalInnerWidth + 2 * goalPostDiameter, "field.penaltyAreaWidth", penaltyAreaWidth);
  less("goal.depth", goalDepth, "field.borderStripWidth", borderStripWidth);
  less("lineWidth", lineWidth, "field.penaltyCrossSize", penaltyCrossSize);
}

FieldModel FieldModel::from(const FieldDimensions& d) {
  using V = Eigen::Vector2d;
  using T = FieldIntersection::Type;
  FieldModel m;
  m.dims = d;
  const double hl = d.length / 2, hw = d.width / 2;
  m.centerCircleRadius = d.centerCircleDiameter / 2;
  m.centerMark = V(0, 0);
  m.centerCircleCenter = V(0, 0);
  m.penaltyCrosses = {V(-hl + d.penaltyCrossDistance, 0), V(hl - d.penaltyCrossDistance, 0)};

  auto line = [&](std::string name, V a, V b) { m.lines.push_back({std::move(name), a, b}); };
  auto cross = [&](T type, V p) { m.intersections.push_back({type, p}); };

  // Outer lines and the halfway line. "left" is +y (left when facing the opponent goal).
  line("own_goal_line", V(-hl, -hw), V(-hl, hw));
  line("opp_goal_line", V(hl, -hw), V(hl, hw));
  line("left_side_line", V(-hl, hw), V(hl, hw));
  line("right_side_line", V(-hl, -hw), V(hl, -hw));
  line("halfway_line", V(0, -hw), V(0, hw));
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) cross(T::L, V(sx * hl, sy * hw));
  for (double sy : {-1.0, 1.0}) cross(T::T, V(0, sy * hw));
  for (double sy : {-1.0, 1.0}) cross(T::X, V(0, sy * m.centerCircleRadius));

  // A box in front of each goal (penalty area, goal box): front line, two sides, the front
  // corners (L) and where the sides meet the goal line (T).
  auto box = [&](const std::string& what, double boxLength, double boxWidth) {
    for (double sx : {-1.0, 1.0}) {
      const std::string prefix = sx < 0 ? "own_" : "opp_";
      const double goalX = sx * hl, frontX = sx * (hl - boxLength), hy = boxWidth / 2;
      line(prefix + what + "_front", V(frontX, -hy), V(frontX, hy));
      line(prefix + what + "_left", V(goalX, hy), V(frontX, hy));
      line(prefix + what + "_right", V(goalX, -hy), V(frontX, -hy));
      for (double sy : {-1.0, 1.0}) {
        cross(T::L, V(frontX, sy * hy));
        cross(T::T, V(goalX, sy * hy));
      }
    }
  };
  box("penalty_area", d.penaltyAreaLength, d.penaltyAreaWidth);
  if (d.hasGoalBox) box("goal_box", d.goalBoxAreaLength, d.goalBoxAreaWidth);
  return m;
}

}  // namespace nao
