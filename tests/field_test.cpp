// FieldDimensions parsing/validation and the FieldModel derived from it.
#include <gtest/gtest.h>

#include <filesystem>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string>

#include "perception/FieldDimensions.h"
#include "robot/Error.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

std::string configPath(const std::string& name) { return std::string(NAO_SOURCE_DIR) + "/config/" + name; }

const char* kStandard = R"({
  "field": {"length": 9.0, "width": 6.0, "penaltyCrossSize": 0.1,
            "goalBoxAreaLength": 0.6, "goalBoxAreaWidth": 2.2,
            "penaltyAreaLength": 1.65, "penaltyAreaWidth": 4.0,
            "penaltyCrossDistance": 1.3, "centerCircleDiameter": 1.5,
            "borderStripWidth": 0.7},
  "goal": {"postDiameter": 0.1, "height": 0.8, "innerWidth": 1.5, "depth": 0.5}
})";

// A scratch directory for bad files, removed at the end.
class FieldFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("nao_field_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // The standard text with one "key": value pair replaced (value as JSON text) or removed.
  static std::string edit(const std::string& key, const std::string& value, bool remove = false) {
    std::string text = kStandard;
    const std::string needle = "\"" + key + "\": ";
    const auto pos = text.find(needle);
    EXPECT_NE(pos, std::string::npos) << key;
    auto end = text.find_first_of(",}", pos + needle.size());
    if (!remove) return text.substr(0, pos + needle.size()) + value + text.substr(end);
    // Drop the pair with the comma after it, or, for the last pair, the comma before it.
    if (text[end] == ',') return text.substr(0, pos) + text.substr(end + 1);
    return text.substr(0, text.rfind(',', pos)) + text.substr(end);
  }
  // Loading `text` from a file must throw one line naming the file and containing `expected`.
  void expectError(const std::string& text, const std::string& expected) {
    const std::string path = write("bad.json", text);
    try {
      FieldDimensions::load(path);
      ADD_FAILURE() << "no error for a file that should give '" << expected << "'";
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(e.where(), path);
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      EXPECT_NE(msg.find(expected), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  fs::path dir_;
};

TEST(FieldDimensions, StandardFile) {
  const auto d = FieldDimensions::load(configPath("field_dimensions.json"));
  EXPECT_DOUBLE_EQ(d.length, 9.0);
  EXPECT_DOUBLE_EQ(d.width, 6.0);
  EXPECT_TRUE(d.hasGoalBox);
  EXPECT_DOUBLE_EQ(d.goalBoxAreaLength, 0.6);
  EXPECT_DOUBLE_EQ(d.goalBoxAreaWidth, 2.2);
  EXPECT_DOUBLE_EQ(d.penaltyAreaLength, 1.65);
  EXPECT_DOUBLE_EQ(d.penaltyAreaWidth, 4.0);
  EXPECT_DOUBLE_EQ(d.penaltyCrossDistance, 1.3);
  EXPECT_DOUBLE_EQ(d.penaltyCrossSize, 0.1);
  EXPECT_DOUBLE_EQ(d.centerCircleDiameter, 1.5);
  EXPECT_DOUBLE_EQ(d.borderStripWidth, 0.7);
  EXPECT_DOUBLE_EQ(d.goalPostDiameter, 0.1);
  EXPECT_DOUBLE_EQ(d.goalHeight, 0.8);
  EXPECT_DOUBLE_EQ(d.goalInnerWidth, 1.5);
  EXPECT_DOUBLE_EQ(d.goalDepth, 0.5);
  EXPECT_DOUBLE_EQ(d.lineWidth, 0.05);
}

TEST(FieldDimensions, File2019HasNoGoalBox) {
  const auto d = FieldDimensions::load(configPath("field_dimensions_2019.json"));
  EXPECT_FALSE(d.hasGoalBox);
  EXPECT_DOUBLE_EQ(d.length, 9.0);
  EXPECT_DOUBLE_EQ(d.penaltyAreaLength, 0.6);  // the 2019 rules' penalty area
  EXPECT_DOUBLE_EQ(d.penaltyAreaWidth, 2.2);
}

TEST(FieldDimensions, ReducedFile) {
  const auto d = FieldDimensions::load(configPath("field_dimensions_reduced.json"));
  EXPECT_DOUBLE_EQ(d.length, 7.5);
  EXPECT_DOUBLE_EQ(d.width, 5.0);
  EXPECT_TRUE(d.hasGoalBox);
  const auto m = FieldModel::from(d);
  EXPECT_DOUBLE_EQ(m.halfLength(), 3.75);
  EXPECT_DOUBLE_EQ(m.halfWidth(), 2.5);
}

TEST(FieldDimensions, ParseNamesTheSource) {
  EXPECT_NO_THROW(FieldDimensions::parse(kStandard, "inline"));
  try {
    FieldDimensions::parse("[1, 2]", "packet");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "packet: top level: must be an object");
  }
}

TEST_F(FieldFiles, MissingFile) {
  const std::string path = (dir_ / "nope.json").string();
  try {
    FieldDimensions::load(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": file not found");
  }
}

TEST_F(FieldFiles, DirectoryIsNotAFile) {
  try {
    FieldDimensions::load(dir_.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos);
  }
}

TEST_F(FieldFiles, MalformedJsonGivesLineAndColumn) {
  // Line 3 lacks a comma after the value.
  expectError("{\n  \"field\": {\"length\": 9.0,\n            \"width\": 6.0\n            \"x\": 1}\n}",
              "JSON syntax error at line 4, column ");
  expectError("", "JSON syntax error at line 1");
  expectError("{\"field\": {\"length\": NaN}}", "JSON syntax error at line 1, column ");
}

TEST_F(FieldFiles, MissingKeys) {
  expectError(edit("penaltyAreaWidth", "", true), "field.penaltyAreaWidth: missing");
  expectError(edit("length", "", true), "field.length: missing");
  expectError(edit("depth", "", true), "goal.depth: missing");
  expectError(edit("postDiameter", "", true), "goal.postDiameter: missing");
  expectError(R"({"field": {}})", "field.length: missing");
  expectError(R"({"goal": {}})", "field: missing");
  expectError(R"({"field": 3, "goal": {}})", "field: must be an object");
}

TEST_F(FieldFiles, OnlyOneGoalBoxKey) {
  expectError(edit("goalBoxAreaWidth", "", true), "field.goalBoxAreaWidth: missing");
  expectError(edit("goalBoxAreaLength", "", true), "field.goalBoxAreaLength: missing");
}

TEST_F(FieldFiles, WrongTypes) {
  expectError(edit("width", "\"NaN\""), "field.width: must be a number (got string)");
  expectError(edit("length", "null"), "field.length: must be a number (got null)");
  expectError(edit("height", "true"), "goal.height: must be a number (got boolean)");
  expectError(edit("penaltyCrossSize", "[0.1]"), "field.penaltyCrossSize: must be a number (got array)");
}

TEST_F(FieldFiles, NonPositiveAndNonFinite) {
  expectError(edit("length", "-9"), "field.length: must be > 0");
  expectError(edit("penaltyAreaWidth", "0"), "field.penaltyAreaWidth: must be > 0");
  expectError(edit("goalBoxAreaLength", "-0.6"), "field.goalBoxAreaLength: must be > 0");
  expectError(edit("innerWidth", "-1.5"), "goal.innerWidth: must be > 0");
  // 1e999 overflows a double: nlohmann either rejects it or gives inf; both must name the file.
  const std::string path = write("huge.json", edit("borderStripWidth", "1e999"));
  EXPECT_THROW(FieldDimensions::load(path), Error);
}

TEST_F(FieldFiles, InconsistentSizes) {
  expectError(edit("penaltyAreaWidth", "7.0"), "field.penaltyAreaWidth: 7 must be < field.width (6)");
  expectError(edit("penaltyAreaLength", "4.6"), "field.penaltyAreaLength");
  expectError(edit("goalBoxAreaWidth", "4.5"), "field.goalBoxAreaWidth");
  expectError(edit("goalBoxAreaLength", "1.7"), "field.goalBoxAreaLength");
  expectError(edit("penaltyCrossDistance", "4.5"), "field.penaltyCrossDistance");
  expectError(edit("centerCircleDiameter", "6.5"), "field.centerCircleDiameter");
  expectError(edit("depth", "0.8"), "goal.depth");
  expectError(edit("innerWidth", "4.0"), "goal.innerWidth");
  // Absurd sizes (metres typed as millimetres) are refused, naming the key.
  expectError(edit("length", "9000"), "field.length");
  expectError(edit("borderStripWidth", "700"), "field.borderStripWidth");
  expectError(edit("height", "800"), "goal.height");
}

TEST(FieldDimensions, ValidateProgrammatic) {
  FieldDimensions d;
  EXPECT_NO_THROW(d.validate("defaults"));
  d.width = std::numeric_limits<double>::quiet_NaN();
  try {
    d.validate("defaults");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "defaults: field.width: must be finite");
  }
}

// ---- FieldModel ----

std::map<std::string, FieldLine> byName(const FieldModel& m) {
  std::map<std::string, FieldLine> out;
  for (const auto& l : m.lines) out.emplace(l.name, l);
  return out;
}

int count(const FieldModel& m, FieldIntersection::Type t) {
  int n = 0;
  for (const auto& i : m.intersections) n += i.type == t;
  return n;
}

bool hasIntersection(const FieldModel& m, FieldIntersection::Type t, double x, double y) {
  for (const auto& i : m.intersections)
    if (i.type == t && (i.position - Eigen::Vector2d(x, y)).norm() < 1e-12) return true;
  return false;
}

TEST(FieldModel, StandardField) {
  const auto m = FieldModel::from(FieldDimensions::load(configPath("field_dimensions.json")));
  using T = FieldIntersection::Type;
  // 4 outer + halfway + 2 x 3 penalty area + 2 x 3 goal box.
  EXPECT_EQ(m.lines.size(), 17u);
  EXPECT_EQ(m.intersections.size(), 24u);
  EXPECT_EQ(count(m, T::L), 12);  // 4 field corners, 4 penalty area, 4 goal box corners
  EXPECT_EQ(count(m, T::T), 10);  // 2 halfway/side, 4 penalty area/goal line, 4 goal box/goal line
  EXPECT_EQ(count(m, T::X), 2);   // centre circle x halfway line
  const auto lines = byName(m);
  EXPECT_EQ(lines.size(), m.lines.size()) << "line names must be unique";
  for (const char* name : {"own_goal_line", "opp_goal_line", "left_side_line", "right_side_line", "halfway_line",
                           "own_penalty_area_front", "own_penalty_area_left", "own_penalty_area_right",
                           "opp_penalty_area_front", "opp_penalty_area_left", "opp_penalty_area_right",
                           "own_goal_box_front", "own_goal_box_left", "own_goal_box_right", "opp_goal_box_front",
                           "opp_goal_box_left", "opp_goal_box_right"})
    EXPECT_TRUE(lines.count(name)) << name;
  const auto& gb = lines.at("opp_goal_box_front");
  EXPECT_DOUBLE_EQ(gb.from.x(), 4.5 - 0.6);
  EXPECT_DOUBLE_EQ(gb.to.x(), 4.5 - 0.6);
  EXPECT_DOUBLE_EQ(std::abs(gb.from.y() - gb.to.y()), 2.2);
  EXPECT_DOUBLE_EQ(lines.at("own_goal_box_front").from.x(), -(4.5 - 0.6));
  EXPECT_DOUBLE_EQ(lines.at("own_penalty_area_front").from.x(), -(4.5 - 1.65));
  const auto& pl = lines.at("opp_penalty_area_left");
  EXPECT_DOUBLE_EQ(pl.from.y(), 2.0);
  EXPECT_DOUBLE_EQ(pl.to.y(), 2.0);
  EXPECT_DOUBLE_EQ(lines.at("left_side_line").from.y(), 3.0);
  EXPECT_DOUBLE_EQ((lines.at("halfway_line").to - lines.at("halfway_line").from).norm(), 6.0);

  EXPECT_TRUE(hasIntersection(m, T::L, 4.5, 3.0));
  EXPECT_TRUE(hasIntersection(m, T::T, 0, -3.0));
  EXPECT_TRUE(hasIntersection(m, T::X, 0, 0.75));
  EXPECT_TRUE(hasIntersection(m, T::X, 0, -0.75));
  EXPECT_TRUE(hasIntersection(m, T::L, -2.85, 2.0));
  EXPECT_TRUE(hasIntersection(m, T::T, -4.5, 2.0));
  EXPECT_TRUE(hasIntersection(m, T::L, 3.9, -1.1));
  EXPECT_TRUE(hasIntersection(m, T::T, 4.5, -1.1));

  ASSERT_EQ(m.penaltyCrosses.size(), 2u);
  EXPECT_DOUBLE_EQ(m.penaltyCrosses[0].x(), -3.2);
  EXPECT_DOUBLE_EQ(m.penaltyCrosses[1].x(), 3.2);
  EXPECT_DOUBLE_EQ(m.centerCircleRadius, 0.75);
  EXPECT_EQ(m.centerMark, Eigen::Vector2d(0, 0));
}

TEST(FieldModel, Field2019WithoutGoalBox) {
  const auto m = FieldModel::from(FieldDimensions::load(configPath("field_dimensions_2019.json")));
  EXPECT_EQ(m.lines.size(), 11u);
  EXPECT_EQ(m.intersections.size(), 16u);
  for (const auto& l : m.lines) EXPECT_EQ(l.name.find("goal_box"), std::string::npos) << l.name;
  EXPECT_DOUBLE_EQ(byName(m).at("opp_penalty_area_front").from.x(), 3.9);
}

TEST(FieldModel, LinesHaveLengthAndEndsOnIntersections) {
  // Every straight line's two ends are intersections (the outer/box lines end on L or T joints).
  const auto m = FieldModel::from(FieldDimensions::load(configPath("field_dimensions.json")));
  for (const auto& l : m.lines) {
    EXPECT_GT((l.to - l.from).norm(), 0.5) << l.name;
    for (const auto& p : {l.from, l.to}) {
      bool found = false;
      for (const auto& i : m.intersections) found |= (i.position - p).norm() < 1e-12;
      EXPECT_TRUE(found) << l.name << " end " << p.transpose();
    }
  }
}

}  // namespace
}  // namespace nao
