#pragma once
// The SPL field as the venue's field_dimensions.json describes it. Both the simulator's
// field and the robot program's field model are built from this one struct, so a reduced
// field is one edit of the file.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace nao {

struct FieldDimensions {
  // field.*
  double length = 9.0, width = 6.0;
  double penaltyCrossSize = 0.1;
  bool hasGoalBox = true;  // false for 2019-style files (no goalBoxArea* keys)
  double goalBoxAreaLength = 0.6, goalBoxAreaWidth = 2.2;
  double penaltyAreaLength = 1.65, penaltyAreaWidth = 4.0;
  double penaltyCrossDistance = 1.3;
  double centerCircleDiameter = 1.5;
  double borderStripWidth = 0.7;
  // goal.*
  double goalPostDiameter = 0.1, goalHeight = 0.8, goalInnerWidth = 1.5, goalDepth = 0.5;
  // Not in the file: the SPL rule value.
  double lineWidth = 0.05;

  // Throws nao::Error naming the file and the key on a missing/ill-typed/implausible value.
  static FieldDimensions load(const std::string& path);
  static FieldDimensions parse(const std::string& jsonText, const std::string& sourceName);
  // Throws nao::Error(sourceName, ...) if a value is non-finite, not positive, or the parts do not fit.
  void validate(const std::string& sourceName) const;
};

// A straight field line, by the centre of its paint (field frame, m).
struct FieldLine {
  std::string name;  // e.g. "own_goal_line", "opp_goal_box_front"
  Eigen::Vector2d from, to;
};

// A point where line centres meet, typed as B-Human does: L, T or X.
struct FieldIntersection {
  enum class Type { L, T, X };
  Type type;
  Eigen::Vector2d position;
};

// Everything painted on the field, derived from FieldDimensions.
struct FieldModel {
  FieldDimensions dims;
  std::vector<FieldLine> lines;          // straight lines (not the circle, not the penalty crosses)
  std::vector<FieldIntersection> intersections;
  Eigen::Vector2d centerCircleCenter{0, 0};
  double centerCircleRadius = 0.75;      // to the line centre
  std::vector<Eigen::Vector2d> penaltyCrosses;
  Eigen::Vector2d centerMark{0, 0};      // the centre dash / spot

  static FieldModel from(const FieldDimensions& d);
  double halfLength() const { return dims.length / 2; }
  double halfWidth() const { return dims.width / 2; }
};

}  // namespace nao
