// match --images (scenarios/Match.h, MatchOptions::imagesDir): the field from above at each point
// and referee call, every 10 simulated s and at the end, named by the event's index in the log,
// the ball drawn where the simulator had it; with the vision, both robots' camera images too,
// and in them the other robot in its team's jersey.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "perception/FieldDimensions.h"
#include "robot/Paths.h"
#include "scenarios/Match.h"

namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  return d;
}

bool listed(const nlohmann::json& images, const std::string& file) {
  for (const auto& f : images)
    if (f == file) return true;
  return false;
}

TEST(MatchImages, APointsPictureShowsTheBallWhereItScored) {
  nao::sim::MatchOptions o;
  o.field = nao::FieldDimensions::load(nao::dataPath("config/field_dimensions.json"));
  o.situation = nao::sim::loadSituation(nao::dataPath("tests/situations/goal.json"));
  o.percepts = "oracle";
  const fs::path dir = freshDir("match_images_goal");
  o.imagesDir = dir.string();
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  const nlohmann::json& j = r.json;
  ASSERT_TRUE(j.contains("images")) << j.dump();
  std::size_t index = 0;
  const nlohmann::json* point = nullptr;
  for (std::size_t i = 0; i < j["events"].size(); ++i)
    if (j["events"][i]["kind"] == "point") index = i, point = &j["events"][i];
  ASSERT_NE(point, nullptr) << j["events"].dump();
  char name[64];
  std::snprintf(name, sizeof name, "event_%03zu_point_home_field.png", index);
  EXPECT_TRUE(listed(j["images"], name)) << j["images"].dump();
  EXPECT_TRUE(listed(j["images"], "final_field.png")) << j["images"].dump();
  // The fast percept mode renders nothing: no camera pictures.
  for (const auto& f : j["images"]) EXPECT_EQ(f.get<std::string>().find("_top"), std::string::npos) << f;
  for (const auto& f : j["images"]) EXPECT_TRUE(fs::exists(dir / f.get<std::string>())) << f;

  // The ball (orange) where the referee saw the goal: within a ball's radius of (at), at 80 px/m.
  const cv::Mat view = cv::imread((dir / name).string());
  ASSERT_FALSE(view.empty());
  const auto& d = o.field;
  const double x = (*point)["at"][0].get<double>(), y = (*point)["at"][1].get<double>();
  const int u = static_cast<int>(std::lround((x + d.length / 2 + d.borderStripWidth) * 80));
  const int v = static_cast<int>(std::lround((d.width / 2 + d.borderStripWidth - y) * 80));
  int orange = 0;
  for (int dv = -8; dv <= 8; ++dv)
    for (int du = -8; du <= 8; ++du) {
      if (v + dv < 0 || v + dv >= view.rows || u + du < 0 || u + du >= view.cols) continue;
      const cv::Vec3b p = view.at<cv::Vec3b>(v + dv, u + du);  // BGR
      orange += p[2] > 200 && p[1] > 100 && p[1] < 180 && p[0] < 60;
    }
  EXPECT_GT(orange, 10) << "no ball drawn near (" << x << ", " << y << ") = pixel (" << u << ", " << v << ")";
}

TEST(MatchImages, WithTheVisionBothRobotsCameraImagesAreWritten) {
  nao::sim::MatchOptions o;
  o.field = nao::FieldDimensions::load(nao::dataPath("config/field_dimensions.json"));
  o.seconds = 1;
  const fs::path dir = freshDir("match_images_vision");
  o.imagesDir = dir.string();
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  for (const char* team : {"home", "away"})
    for (const auto& [camera, width, height] : {std::tuple{"top", 640, 480}, std::tuple{"bottom", 320, 240}}) {
      const std::string file = std::string("final_") + team + "_" + camera + ".png";
      EXPECT_TRUE(listed(r.json["images"], file)) << r.json["images"].dump();
      const cv::Mat image = cv::imread((dir / file).string());
      ASSERT_FALSE(image.empty()) << file;
      EXPECT_EQ(image.cols, width) << file;
      EXPECT_EQ(image.rows, height) << file;
    }
  EXPECT_FALSE(cv::imread((dir / "final_field.png").string()).empty());
}

// Jerseys: each robot's torso in its team's field player colour (home blue, away red: the
// colours the GameController sends). The home robot, facing a standing away robot 1.5 m ahead,
// sees red in its top camera, and its own team's blue nowhere.
TEST(MatchImages, TheOpponentWearsItsTeamsJersey) {
  const fs::path dir = freshDir("match_images_jersey");
  fs::create_directories(dir);
  std::ofstream(dir / "facing.json") << R"({"state": "PLAYING", "seconds": 1.5,
    "robots": [{"team": "home", "pose": [-1.0, 0.0, 0], "program": true},
               {"team": "away", "pose": [0.5, 0.0, 180], "script": [{"t": 0, "do": "stand"}]}]})";
  nao::sim::MatchOptions o;
  o.field = nao::FieldDimensions::load(nao::dataPath("config/field_dimensions.json"));
  o.situation = nao::sim::loadSituation((dir / "facing.json").string());
  o.imagesDir = (dir / "out").string();
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  EXPECT_EQ(r.json["robots"][0]["jersey"], "blue");
  EXPECT_EQ(r.json["robots"][1]["jersey"], "red");
  const cv::Mat top = cv::imread((dir / "out" / "final_home_top.png").string());
  ASSERT_FALSE(top.empty()) << r.json["images"].dump();
  int red = 0, blue = 0;
  for (int v = 0; v < top.rows; ++v)
    for (int u = 0; u < top.cols; ++u) {
      const cv::Vec3b p = top.at<cv::Vec3b>(v, u);  // BGR
      // Hue, not brightness: the exposure is the camera's (the program meters the near field).
      red += p[2] > 50 && p[2] > 2 * p[1] + 30 && p[2] > 2 * p[0] + 30;
      blue += p[0] > 50 && p[0] > 2 * p[2] + 30 && p[0] > p[1] + 30;
    }
  EXPECT_GT(red, 300) << "the away robot's red torso is not in the home robot's view";
  EXPECT_EQ(blue, 0);
}

}  // namespace
