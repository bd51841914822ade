// Real goal-box images with the robot's recorded camera matrices and line labels
// (../shared/data/real-goalbox-images, HULKs, GPL-3.0; read in place): the matrix reader
// (frames, bad files), a sample carrying a recorded pose measured as the joint-based one, and
// perceive --camera-matrix and eval real on the real frames against their labels.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "controllers/StandController.h"
#include "perception/RecordedCameraMatrix.h"
#include "perception/calibration/CalibrationCost.h"
#include "perception/calibration/CalibrationViews.h"
#include "perception/calibration/SyntheticSamples.h"
#include "robot/Error.h"
#include "support/RunCommand.h"

namespace nao {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180;
const std::string kDir = std::string(NAO_SHARED_DIR) + "/data/real-goalbox-images";

std::vector<std::string> frames() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::string tempFile(const std::string& name, const std::string& content) {
  const std::string path = std::string(::testing::TempDir()) + name;
  std::ofstream(path) << content;
  return path;
}

// perceive on a real frame with its recorded matrix: the JSON it prints.
nlohmann::json perceiveJson(const std::string& stem, const char* camera) {
  const auto r = test::runCommand("perceive " + stem + ".jpg --camera " + camera + " --camera-matrix " + stem + ".json --json -");
  EXPECT_EQ(r.code, 0) << r.out;
  return nlohmann::json::parse(r.out.substr(r.out.find('{')));
}

// The farther of a label's two points from a sample line (its "image" end points).
double labelOffPx(const nlohmann::json& line, const LabelledLine& label) {
  const Eigen::Vector2d a(line["image"][0][0], line["image"][0][1]), b(line["image"][1][0], line["image"][1][1]);
  const Eigen::Vector2d d = (b - a).normalized();
  double worst = 0;
  for (const auto& p : {label.a, label.b}) worst = std::max(worst, std::abs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())));
  return worst;
}

// The labelled lines' direction on the ground through the recorded matrix.
Eigen::Vector2d groundDirection(const CameraMatrix& cm, const LabelledLine& l) {
  const auto a = cm.pixelToGround(l.a), b = cm.pixelToGround(l.b);
  EXPECT_TRUE(a && b) << l.name;
  return a && b ? Eigen::Vector2d((*b - *a).normalized()) : Eigen::Vector2d::UnitX();
}

// The frames' conventions are ours: through every recorded matrix the painted goal box's lines
// meet at right angles on the ground and its two long lines are parallel (the paint is the
// independent truth; the matrices are the robot's own estimates, so a few degrees are allowed).
TEST(RecordedCameraMatrix, EveryRealFrameMapsTheGoalBoxToRightAnglesOnTheGround) {
  const auto files = frames();
  ASSERT_EQ(files.size(), 39u);
  int top = 0;
  for (const auto& f : files) {
    const RecordedCameraMatrix r = RecordedCameraMatrix::read(f);
    top += r.camera == CameraId::Top;
    ASSERT_EQ(r.lines.size(), 3u) << f;
    // A standing NAO's cameras: about 0.4-0.5 m above the floor.
    EXPECT_GT(r.matrix.pose.translation().z(), 0.37) << f;
    EXPECT_LT(r.matrix.pose.translation().z(), 0.52) << f;
    const Eigen::Vector2d border = groundDirection(r.matrix, *r.line("border_line"));
    const Eigen::Vector2d box = groundDirection(r.matrix, *r.line("goal_box_line"));
    const Eigen::Vector2d side = groundDirection(r.matrix, *r.line("connecting_line"));
    EXPECT_LT(std::abs(side.dot(border)), std::sin(10 * kDeg)) << f;
    EXPECT_LT(std::abs(side.dot(box)), std::sin(10 * kDeg)) << f;
    EXPECT_GT(std::abs(border.dot(box)), std::cos(4 * kDeg)) << f;
    // The ground is in front of the camera: the horizon lies above the labelled lines.
    for (const auto& l : r.lines) EXPECT_FALSE(r.matrix.isAboveHorizon(l.a)) << f << " " << l.name;
  }
  EXPECT_EQ(top, 21);
}

TEST(RecordedCameraMatrix, ScalesItsIntrinsicsToTheImage) {
  const RecordedCameraMatrix r = RecordedCameraMatrix::read(frames().front());
  const CameraMatrix half = r.forImage(320, 240);
  EXPECT_DOUBLE_EQ(half.intrinsics.fx, r.matrix.intrinsics.fx / 2);
  EXPECT_DOUBLE_EQ(half.intrinsics.cy, r.matrix.intrinsics.cy / 2);
  // The same ground point lands on the same place of the scaled image.
  const auto p = r.matrix.projectGround({2.0, 0.3}), q = half.projectGround({2.0, 0.3});
  ASSERT_TRUE(p && q);
  EXPECT_NEAR(q->x(), p->x() / 2, 1e-9);
  EXPECT_NEAR(q->y(), p->y() / 2, 1e-9);
}

TEST(RecordedCameraMatrix, BadFilesNameTheFieldInOneLine) {
  const std::string good = slurp(frames().front());
  nlohmann::json base = nlohmann::json::parse(good);
  struct Case {
    std::function<void(nlohmann::json&)> damage;
    std::string field;
  };
  const std::vector<Case> cases = {
      {[](auto& j) { j["camera_matrix"]["camera_to_ground"]["rotation"] = {0.1, 0.2, 0.3, 1.4}; },
       "camera_matrix.camera_to_ground.rotation: not a unit quaternion"},
      {[](auto& j) { j["camera_matrix"].erase("camera_to_ground"); }, "camera_matrix.camera_to_ground: missing"},
      {[](auto& j) { j["camera_matrix"]["camera_to_ground"].erase("translation"); },
       "camera_matrix.camera_to_ground.translation: missing"},
      {[](auto& j) { j["camera_matrix"]["focal_length"] = {608.0}; }, "camera_matrix.focal_length: must be an array of 2"},
      {[](auto& j) { j["camera_matrix"]["focal_length"][1] = "600"; }, "camera_matrix.focal_length[1]: must be a number"},
      {[](auto& j) { j["camera_matrix"]["focal_length"][0] = -5; }, "camera_matrix.focal_length[0]"},
      {[](auto& j) { j["camera_matrix"]["optical_center"] = {900, 240}; }, "camera_matrix.optical_center"},
      {[](auto& j) { j["camera_matrix"]["camera_to_ground"]["translation"][2] = 3.0; },
       "camera_matrix.camera_to_ground.translation[2]"},
      {[](auto& j) { j["position"] = "Left"; }, "position: must be"},
      {[](auto& j) { j.erase("position"); }, "position: missing"},
      {[](auto& j) { j["crossings"].erase("border_line_1"); }, "crossings.border_line_1: missing"},
      {[](auto& j) { j["crossings"]["goal_box_line_0"] = {1, 2, 3}; }, "crossings.goal_box_line_0"},
  };
  for (const auto& c : cases) {
    nlohmann::json j = base;
    c.damage(j);
    try {
      RecordedCameraMatrix::parse(j.dump(), "m.json");
      ADD_FAILURE() << "accepted: " << c.field;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("m.json: ", 0), 0u) << what;
      EXPECT_NE(what.find(c.field), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  for (const std::string text : {"", "{", "[1,2]", "{\"position\": \"Top\"}", "null"})
    EXPECT_THROW(RecordedCameraMatrix::parse(text, "m.json"), Error) << text;
  EXPECT_THROW(RecordedCameraMatrix::read("/nonexistent/m.json"), Error);
}

// A sample with a recorded camera pose (a real image: no joint angles) must measure the goal box
// as the joint-based sample of the same view does, with and without camera offsets.
TEST(RecordedCameraMatrix, ASampleWithARecordedPoseMeasuresAsTheJointBasedOne) {
  const FieldDimensions field;
  calibration::SyntheticScene scene;
  scene.side = calibration::ownGoalBoxSide(field, -1);
  scene.robotPose = {-3.6, -1.5, 100 * kDeg};
  JointArray joints = StandController::standPosture();
  joints[HeadYaw] = -20 * kDeg;
  joints[HeadPitch] = 10 * kDeg;
  const CameraCalibration truth = CameraCalibration::fromArray({0, 0, 1.2 * kDeg, -0.8 * kDeg, 0, 0});
  const auto sample = calibration::synthesizeSample(scene, joints, CameraId::Top, truth, CameraIntrinsics::nominal(CameraId::Top));
  ASSERT_TRUE(sample);
  calibration::CalibrationSample recorded = *sample;
  recorded.cameraPose = computeCameraMatrix(joints, scene.imuAngle, CameraId::Top, {}, sample->intrinsics).pose;
  recorded.joints = {};
  const calibration::CostOptions co = calibration::CostOptions::forField(field);
  const calibration::CalibrationCost a({*sample}, co), b({recorded}, co);
  for (const auto& x : {calibration::Params{}, truth.toArray()}) {
    const auto ra = a.sampleResiduals(x, 0), rb = b.sampleResiduals(x, 0);
    ASSERT_TRUE(ra.projected && rb.projected);
    EXPECT_NEAR(ra.angle1Deg, rb.angle1Deg, 1e-9);
    EXPECT_NEAR(ra.angle2Deg, rb.angle2Deg, 1e-9);
    EXPECT_NEAR(ra.depthErrorM, rb.depthErrorM, 1e-9);
  }
  // With the true camera offsets the goal box is exact; without them it is not.
  EXPECT_NEAR(b.sampleResiduals(truth.toArray(), 0).angle1Deg, 0, 1e-6);
  EXPECT_GT(std::abs(b.sampleResiduals({}, 0).angle1Deg) + std::abs(b.sampleResiduals({}, 0).depthErrorM), 1e-3);
}

using test::runCommand;

void expectOneLineErrorIn(const test::CommandResult& r, const std::string& what1, const std::string& what2) {
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find(what1), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(what2), std::string::npos) << r.out;
}

TEST(PerceiveRecorded, ReportsTheCalibrationSampleOfARealImage) {
  const std::string stem = kDir + "/1687086108";  // a bottom-camera frame that gives a sample
  const std::string json = std::string(::testing::TempDir()) + "perceive_real.json";
  const std::string png = std::string(::testing::TempDir()) + "perceive_real.png";
  const auto r = runCommand("perceive " + stem + ".jpg --camera bottom --camera-matrix " + stem + ".json --json " + json +
                            " --out " + png);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(j["camera_matrix"], stem + ".json");
  const auto& s = j["calibration_sample"];
  ASSERT_TRUE(s["accepted"].get<bool>()) << s.dump();
  // Its short line is the labelled connecting line (within 3 px of both labelled points).
  EXPECT_LT(labelOffPx(s["lines"]["short"], *RecordedCameraMatrix::read(stem + ".json").line("connecting_line")), 3.0);
  EXPECT_LT(std::abs(s["residuals"]["right_angle1_deg"].get<double>()), 5.0);
  EXPECT_TRUE(fs::exists(png));

  // A refused one says which check failed.
  const auto r2 = runCommand("perceive " + kDir + "/1687083797.jpg --camera-matrix " + kDir + "/1687083797.json --json -");
  ASSERT_EQ(r2.code, 0) << r2.out;
  const auto j2 = nlohmann::json::parse(r2.out.substr(r2.out.find('{')));
  ASSERT_FALSE(j2["calibration_sample"]["accepted"].get<bool>());
  ASSERT_TRUE(j2["calibration_sample"]["reason"].is_string());
  EXPECT_FALSE(j2["calibration_sample"]["reason"].get<std::string>().empty());
}

// A bottom-camera frame whose goal line runs up to 8 deg below the horizon: refused with the
// long lines held 10 deg below it, accepted (on the labelled lines) with the fallback that lets
// them come 4 deg near; its short line still lies 10 deg below.
TEST(PerceiveRecorded, LongLinesNearTheHorizonGiveASampleOnlyWhereNothingElseDoes) {
  const std::string stem = kDir + "/1687086099";
  const auto j = perceiveJson(stem, "bottom");
  const auto& s = j["calibration_sample"];
  ASSERT_TRUE(s["accepted"].get<bool>()) << s.dump();
  const CameraMatrix cm = RecordedCameraMatrix::read(stem + ".json").matrix;
  auto depressionDeg = [&](const nlohmann::json& p) {
    const Eigen::Vector3d ray = cm.pixelRay(Eigen::Vector2d(p[0], p[1]));
    return std::atan2(-ray.z(), std::hypot(ray.x(), ray.y())) / kDeg;
  };
  double leastLong = 90, leastShort = 90;
  for (const char* line : {"long1", "long2", "short"})
    for (const auto& edge : s["lines"][line]["edges"])
      for (const auto& p : edge) (line[0] == 's' ? leastShort : leastLong) = std::min(line[0] == 's' ? leastShort : leastLong, depressionDeg(p));
  EXPECT_GE(leastShort, 10 - 1e-6);
  EXPECT_LT(leastLong, 10);
  EXPECT_GE(leastLong, 4 - 1e-6);
  EXPECT_LT(labelOffPx(s["lines"]["short"], *RecordedCameraMatrix::read(stem + ".json").line("connecting_line")), 3.0);
}

// A top-camera frame whose short line lies too close to its junctions for the paint edges to be
// measured (the box 3-4 m away): the vision's sub-pixel centre lines stand in as the last
// fallback (ExtractionOptions::visionCentreLines), on the labelled lines. And one where the
// vision saw only a piece of the short line.
TEST(PerceiveRecorded, TheVisionsCentreLinesStandInWhereTheEdgesCannotBeMeasured) {
  const std::string stem = kDir + "/1687083883";
  const auto j = perceiveJson(stem, "top");
  const auto& s = j["calibration_sample"];
  ASSERT_TRUE(s["accepted"].get<bool>()) << s.dump();
  EXPECT_EQ(s["source"], "vision centre lines");
  const RecordedCameraMatrix rec = RecordedCameraMatrix::read(stem + ".json");
  EXPECT_LT(labelOffPx(s["lines"]["short"], *rec.line("connecting_line")), 3.0);
  // The long lines in either order.
  const double goalFirst = std::max(labelOffPx(s["lines"]["long1"], *rec.line("border_line")),
                                    labelOffPx(s["lines"]["long2"], *rec.line("goal_box_line")));
  const double boxFirst = std::max(labelOffPx(s["lines"]["long1"], *rec.line("goal_box_line")),
                                   labelOffPx(s["lines"]["long2"], *rec.line("border_line")));
  EXPECT_LT(std::min(goalFirst, boxFirst), 3.0);
  EXPECT_LT(std::abs(s["residuals"]["right_angle1_deg"].get<double>()), 2.0);
  EXPECT_LT(std::abs(s["residuals"]["right_angle2_deg"].get<double>()), 2.0);

  // A bottom-camera frame where the vision saw only 24 px of the 52 px short line (the finder
  // wants 25): its junctions with the long lines are 52 px apart, so it is the box's side.
  const std::string piece = kDir + "/1687086244";
  const auto jp = perceiveJson(piece, "bottom");
  const auto& sp = jp["calibration_sample"];
  ASSERT_TRUE(sp["accepted"].get<bool>()) << sp.dump();
  EXPECT_EQ(sp["source"], "vision centre lines");
  EXPECT_LT(labelOffPx(sp["lines"]["short"], *RecordedCameraMatrix::read(piece + ".json").line("connecting_line")), 5.0);
  EXPECT_LT(std::abs(sp["residuals"]["right_angle1_deg"].get<double>()), 2.0);
  EXPECT_LT(std::abs(sp["residuals"]["right_angle2_deg"].get<double>()), 2.0);
}

// render --camera-matrix: the simulator's twin of a real frame. Seen through the same recorded
// matrix, the simulated field's goal-box lines lie where the real frame's labels are (the
// labels are the independent truth; the lab's goal box is a few centimetres off the SPL's).
TEST(RenderTwin, TheSimulatedGoalBoxLiesOnTheRealFramesLabels) {
  for (const std::string stem : {"1687083815", "1687086108"}) {
    const std::string mat = kDir + "/" + stem + ".json";
    const std::string twin = std::string(::testing::TempDir()) + "twin_" + stem + ".png";
    const auto r = runCommand("render --camera-matrix " + mat + " --lighting noise=0 --out " + twin + " --json -");
    ASSERT_EQ(r.code, 0) << r.out;
    const auto rj = nlohmann::json::parse(r.out.substr(r.out.find('{')));
    EXPECT_EQ(rj["twin"]["camera_matrix"], mat);
    EXPECT_LT(rj["twin"]["robot_pose"][0].get<double>(), -2.0) << "beside the own goal box";
    const auto p = runCommand("perceive " + twin + " --camera-matrix " + mat + " --json -");
    ASSERT_EQ(p.code, 0) << p.out;
    const auto pj = nlohmann::json::parse(p.out.substr(p.out.find('{')));
    const RecordedCameraMatrix rec = RecordedCameraMatrix::read(mat);
    for (const auto& label : rec.lines) {
      bool found = false;
      for (const auto& l : pj["lines"]) {
        const Eigen::Vector2d a(l["image"][0][0], l["image"][0][1]), b(l["image"][1][0], l["image"][1][1]);
        const Eigen::Vector2d d = (b - a).normalized(), e = (label.b - label.a).normalized();
        auto dist = [&](const Eigen::Vector2d& q) { return std::abs(d.x() * (q.y() - a.y()) - d.y() * (q.x() - a.x())); };
        found = found || (std::abs(d.dot(e)) > std::cos(3 * kDeg) && dist(label.a) < 8 && dist(label.b) < 8);
      }
      EXPECT_TRUE(found) << stem << ": no simulated line on the labelled " << label.name;
    }
    // The twin's camera is the recorded one, on the field.
    const Eigen::Vector3d z(rj["camera"]["position"][0], rj["camera"]["position"][1], rj["camera"]["position"][2]);
    EXPECT_NEAR(z.z(), rec.matrix.pose.translation().z(), 1e-6);
  }
  expectOneLineErrorIn(runCommand("render --camera-matrix " + kDir + "/1687083815.json --pose 0,0,0 --out " +
                                  std::string(::testing::TempDir()) + "t.png"),
                       "--camera-matrix", "--pose");
}


TEST(PerceiveRecorded, BadImagesAndMatricesExitTwoWithOneLine) {
  const std::string img = kDir + "/1687078170.jpg", mat = kDir + "/1687078170.json";
  // A truncated JPEG.
  const std::string bytes = slurp(img);
  const std::string cut = tempFile("truncated.jpg", bytes.substr(0, bytes.size() / 3));
  expectOneLineErrorIn(runCommand("perceive " + cut + " --camera-matrix " + mat), cut, "");
  // Not a NAO camera's size.
  const std::string odd = tempFile("odd.ppm", "P6\n400 300\n255\n" + std::string(400 * 300 * 3, '\x60'));
  expectOneLineErrorIn(runCommand("perceive " + odd), odd, "640x480 or 320x240");
  // A matrix file with a non-unit quaternion, and one without its camera matrix.
  nlohmann::json j = nlohmann::json::parse(slurp(mat));
  j["camera_matrix"]["camera_to_ground"]["rotation"] = {0, 0, 0, 2};
  const std::string bad = tempFile("bad_matrix.json", j.dump());
  expectOneLineErrorIn(runCommand("perceive " + img + " --camera-matrix " + bad), bad,
                     "camera_matrix.camera_to_ground.rotation");
  j.erase("camera_matrix");
  const std::string missing = tempFile("missing_matrix.json", j.dump());
  expectOneLineErrorIn(runCommand("perceive " + img + " --camera-matrix " + missing), missing, "camera_matrix: missing");
  // The file's camera against --camera, and a pose given twice.
  expectOneLineErrorIn(runCommand("perceive " + img + " --camera bottom --camera-matrix " + mat), "--camera", "top camera");
  expectOneLineErrorIn(runCommand("perceive " + img + " --head 10,0 --camera-matrix " + mat), "--camera-matrix", "--head");
  expectOneLineErrorIn(runCommand("eval real --dir /nonexistent/dir"), "--dir", "not found");
  const std::string empty = std::string(::testing::TempDir()) + "eval_real_empty";
  fs::create_directories(empty);
  expectOneLineErrorIn(runCommand("eval real --dir " + empty), "--dir", "no labelled image");
}

// eval real over the 39 frames: the figures are consistent with each other and with the frames,
// no accepted sample holds a line other than the labelled ones, at least 80 % of the frames give
// a sample, and the vision finds each of the three labelled lines in at least 90 % of them (on
// the labelled paint; docs/vision/real/README.md, "How precise are the labels").
TEST(EvalReal, ScoresEveryFrameAgainstItsLabels) {
  const std::string json = std::string(::testing::TempDir()) + "eval_real.json";
  const std::string failures = std::string(::testing::TempDir()) + "eval_real_failures";
  fs::remove_all(failures);
  const auto r = runCommand("eval real --dir " + kDir + " --json " + json + " --failures " + failures);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(j["images"], 39);
  ASSERT_EQ(j["frames"].size(), 39u);
  const auto& s = j["calibration_samples"];
  int accepted = 0, right = 0, imprecise = 0, other = 0, pictures = 0;
  std::map<std::string, int> visionPrecise;
  for (const auto& f : j["frames"]) {
    const bool a = f["calibration_sample"]["accepted"];
    accepted += a;
    const std::string v = f["sample_verdict"];
    right += v == "labelled lines";
    imprecise += v == "labelled lines, imprecise";
    other += v == "other lines";
    if (!a) {
      EXPECT_FALSE(f["calibration_sample"]["reason"].get<std::string>().empty());
    }
    bool allVision = true;
    for (const auto& [name, found] : f["labels_found"].items()) {
      allVision = allVision && found["vision"].get<bool>();
      // The paint's half width widens the 3 px at each labelled point: 5 cm are 1-25 px here.
      for (const auto& t : found["paint_tolerance_px"]) {
        EXPECT_GE(t.get<double>(), 3) << name;
        EXPECT_LE(t.get<double>(), 3 + 12.5) << name;
      }
      // The nearest of the vision's lines: within 3 px / 2 deg exactly when the label counts as
      // found precisely (and then it is found), never further than the same line's 10 px / 5 deg.
      const auto& near = found["vision_nearest"];
      if (near.is_null()) {
        EXPECT_FALSE(found["vision_precise"].get<bool>()) << name;
        continue;
      }
      const bool within = near["angle_deg"].get<double>() <= 2 && near["a_px"].get<double>() <= 3 && near["b_px"].get<double>() <= 3;
      EXPECT_EQ(within, found["vision_precise"].get<bool>()) << name << " " << near.dump();
      if (within) {
        EXPECT_TRUE(found["vision"].get<bool>()) << name;
      }
      EXPECT_LE(near["angle_deg"].get<double>(), 5);
      EXPECT_LE(std::max(near["a_px"].get<double>(), near["b_px"].get<double>()), 10);
      visionPrecise[name] += within;
    }
    const bool failure = !allVision || v != "labelled lines";
    const std::string stem = fs::path(f["image"].get<std::string>()).stem().string();
    EXPECT_EQ(fs::exists(failures + "/" + stem + ".png"), failure) << stem;
    pictures += failure;
  }
  EXPECT_EQ(s["accepted"], accepted);
  EXPECT_EQ(s["labelled_lines"], right);
  EXPECT_EQ(s["labelled_lines_imprecise"], imprecise);
  EXPECT_EQ(s["other_lines"], other);
  EXPECT_EQ(other, 0) << "an accepted sample on lines that are not the goal box's";
  // 32 of 39 measured, 18 of them within 3 px / 2 deg of the labels; the vision finds the goal
  // line and the front line on all 39, the side line on 37 (docs/vision/real/README.md).
  EXPECT_GE(accepted, 0.8 * 39);
  EXPECT_GE(right, 16);
  for (const char* name : {"border_line", "goal_box_line", "connecting_line"})
    EXPECT_GE(j["labels"][name]["vision_rate"].get<double>(), 0.9) << name;
  for (const auto& [name, l] : j["labels"].items())
    EXPECT_EQ(l["found_by_vision_precise"].get<int>(), visionPrecise[name]) << name;
  EXPECT_GT(pictures, 0);
}

// The vision joins a line seen in pieces: on this bottom-camera frame the goal box's side line
// came as a piece of 6 spots and one of 3, each shorter than a line must be (0.25 m), the short
// one's direction too rough to reach the other's ends within the spot tolerance. Joined, the
// line is found where the labels put it (LineParams::mergeReach).
TEST(EvalReal, TheVisionJoinsTheBoxSideLineSeenInPieces) {
  const fs::path dir = fs::path(::testing::TempDir()) / "real_one_frame";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* ext : {".jpg", ".json"})
    fs::copy_file(kDir + "/1687086133" + ext, dir / (std::string("1687086133") + ext));
  const std::string json = (dir / "eval.json").string();
  const auto r = runCommand("eval real --dir " + dir.string() + " --json " + json);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(slurp(json));
  ASSERT_EQ(j["frames"].size(), 1u);
  EXPECT_TRUE(j["frames"][0]["labels_found"]["connecting_line"]["vision_precise"].get<bool>()) << j["frames"][0].dump();
}

// A labelled line is found when the vision's line runs through the labelled paint: on this
// near frame the side line's label ends on the goal line's far edge, 6.8 px from the paint's
// centre where the paint is 16 px wide, so the vision's line on the paint is found but not
// within 3 px of the label. Moved 16 px across (beyond the paint's half width + 3 px at both
// ends), the same label is found by nothing.
TEST(EvalReal, ALabelledLineIsFoundOnItsPaintAndNowhereElse) {
  auto evalWith = [](const std::string& name, double shiftPx) {
    const fs::path dir = fs::path(::testing::TempDir()) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(kDir + "/1687083847.jpg", dir / "1687083847.jpg");
    nlohmann::json label = nlohmann::json::parse(slurp(kDir + "/1687083847.json"));
    auto& c = label["crossings"];
    const double ax = c["connecting_line_0"][0], ay = c["connecting_line_0"][1];
    const double bx = c["connecting_line_1"][0], by = c["connecting_line_1"][1];
    const double len = std::hypot(bx - ax, by - ay), nx = -(by - ay) / len, ny = (bx - ax) / len;
    c["connecting_line_0"] = {ax + shiftPx * nx, ay + shiftPx * ny};
    c["connecting_line_1"] = {bx + shiftPx * nx, by + shiftPx * ny};
    std::ofstream(dir / "1687083847.json") << label.dump();
    const std::string json = (dir / "eval.json").string();
    const auto r = runCommand("eval real --dir " + dir.string() + " --json " + json);
    EXPECT_EQ(r.code, 0) << r.out;
    return nlohmann::json::parse(slurp(json))["frames"][0]["labels_found"]["connecting_line"];
  };
  const auto asLabelled = evalWith("real_label_at_edge", 0);
  EXPECT_TRUE(asLabelled["vision"].get<bool>()) << asLabelled.dump();
  EXPECT_FALSE(asLabelled["vision_precise"].get<bool>()) << asLabelled.dump();
  for (double shift : {-16.0, 16.0}) {
    const auto moved = evalWith("real_label_moved", shift);
    EXPECT_FALSE(moved["vision"].get<bool>()) << shift << " " << moved.dump();
    EXPECT_FALSE(moved["vision_precise"].get<bool>()) << shift;
  }
}

}  // namespace
}  // namespace nao
