// nao-soccer eval real: the vision and the calibration's sample extraction on a folder of real,
// labelled images (the format of ../shared/data/real-goalbox-images/README.md), each with the
// camera matrix the robot recorded with it, scored against the labels:
//   - each labelled line: found by the vision (a FieldLines line through the labelled paint:
//     each labelled point within 3 px + half the paint's imaged width there of it), precisely
//     (within 3 px of both labelled points and 2 deg of the labelled direction), and by the
//     calibration sample;
//   - the calibration sample: accepted, and whether its three lines are the labelled ones (short
//     = connecting_line, the long ones = border_line and goal_box_line); an accepted sample with
//     another line in it is a false goal-box line;
//   - the found lines' angles on the ground with the recorded matrix (right angles, parallels).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SampleReport.h"
#include "apps/SimOptions.h"
#include "perception/RecordedCameraMatrix.h"
#include "perception/vision/Annotate.h"
#include "perception/vision/CameraPipeline.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "sim/ImageIO.h"

namespace nao::cli {
namespace {

namespace fs = std::filesystem;
constexpr double kMaxDistancePx = 3, kMaxAngleDeg = 2;
// A sample line further off than this from its labelled line is another line, not an imprecise
// measurement of the same one (the goal box's lines are 0.6 m and more apart on the ground).
constexpr double kSameLinePx = 10, kSameLineDeg = 5;
const char* const kLabelNames[3] = {"connecting_line", "border_line", "goal_box_line"};

// How far a found image line (a, b) lies from a labelled one: the angle between them and each
// labelled point's distance from the found line.
struct LabelOffset {
  double angleDeg, aPx, bPx;
  bool within(double maxPx, double maxDeg) const { return angleDeg <= maxDeg && aPx <= maxPx && bPx <= maxPx; }
  double score() const { return std::max({angleDeg / kMaxAngleDeg, aPx / kMaxDistancePx, bPx / kMaxDistancePx}); }
};
LabelOffset offsetFrom(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const LabelledLine& label) {
  const Eigen::Vector2d d = (b - a).normalized(), l = (label.b - label.a).normalized();
  auto distance = [&](const Eigen::Vector2d& p) { return std::abs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())); };
  return {std::acos(std::min(1.0, std::abs(d.dot(l)))) * 180 / M_PI, distance(label.a), distance(label.b)};
}

// How wide the painted line is in the image at a labelled point, across the labelled line
// (px), from the recorded camera matrix: the labels are clicked on the paint, at its centre or
// at an edge (docs/vision/real/README.md, "How precise are the labels"). 0 where the point or
// the line's far end does not meet the ground.
double paintWidthPx(const CameraMatrix& cm, const LabelledLine& label, const Eigen::Vector2d& at, double lineWidth) {
  const auto g = cm.pixelToGround(at), ga = cm.pixelToGround(label.a), gb = cm.pixelToGround(label.b);
  if (!g || !ga || !gb || (*gb - *ga).norm() < 1e-6) return 0;
  const Eigen::Vector2d dir = (*gb - *ga).normalized(), normal(-dir.y(), dir.x());
  const auto p = cm.projectGround(*g + normal * lineWidth / 2), q = cm.projectGround(*g - normal * lineWidth / 2);
  if (!p || !q) return 0;
  const Eigen::Vector2d l = (label.b - label.a).normalized();
  return std::abs(l.x() * (q->y() - p->y()) - l.y() * (q->x() - p->x()));
}

// Whether a found image line (a, b) is the labelled one: both labelled points within 3 px of
// the found line, directions within 2 deg.
bool matches(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const LabelledLine& label, double maxPx = kMaxDistancePx,
             double maxDeg = kMaxAngleDeg) {
  return offsetFrom(a, b, label).within(maxPx, maxDeg);
}

// Whether the sample's three lines are the labelled ones (short = connecting line) within the
// given tolerances.
bool sampleIs(const std::array<ImageLine, 3>& sl, const LabelledLine* const byRole[3], double maxPx, double maxDeg) {
  auto m = [&](int k, int role) { return matches(sl[k].from, sl[k].to, *byRole[role], maxPx, maxDeg); };
  return m(0, 0) && ((m(1, 1) && m(2, 2)) || (m(1, 2) && m(2, 1)));
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

int evalRealCommand(const EvalRealOptions& options) {
  const FieldDimensions field = fieldFrom(options.common);
  const VisionGeometry geometry = VisionGeometry::from(field);
  std::vector<std::string> stems;
  for (const auto& e : fs::directory_iterator(options.dir))
    if (e.is_regular_file() && e.path().extension() == ".json") stems.push_back(e.path().stem().string());
  std::sort(stems.begin(), stems.end());
  std::vector<std::pair<std::string, std::string>> frames;  // image, camera matrix
  for (const auto& s : stems)
    for (const char* ext : {".jpg", ".jpeg", ".png"})
      if (fs::is_regular_file(fs::path(options.dir) / (s + ext))) {
        frames.emplace_back((fs::path(options.dir) / (s + ext)).string(), (fs::path(options.dir) / (s + ".json")).string());
        break;
      }
  if (frames.empty()) throw Error("--dir", options.dir + " holds no labelled image (NAME.json beside NAME.jpg or .png)");
  if (!options.failures.empty()) io::makeDirectories(options.failures);

  // The extraction as the robot program's calibrator is configured.
  const calibration::ExtractionOptions eo = robotExtractionOptions(field);
  const bool visionLines = eo.source != calibration::LineSource::Lsd;
  std::map<CameraId, std::unique_ptr<CameraPipeline>> pipelines;

  nlohmann::json rows = nlohmann::json::array();
  std::map<std::string, int> labelled, byVision, byVisionPrecise, bySample;
  int accepted = 0, right = 0, imprecise = 0, wrong = 0, labelledFrames = 0;
  std::map<std::string, int> reasons;
  std::vector<double> sampleAngles, labelAngles, sampleParallel;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& [imagePath, matrixPath] = frames[i];
    const RecordedCameraMatrix rec = RecordedCameraMatrix::read(matrixPath);
    const CameraImage img = sim::readImage(imagePath, 0, 0, rec.camera);
    requireNaoImageSize(img, imagePath);
    const CameraMatrix cm = rec.forImage(img.width, img.height);
    // Labels are for 640x480: scale them with the image.
    std::vector<LabelledLine> labels = rec.lines;
    for (auto& l : labels) {
      l.a = l.a.cwiseProduct(Eigen::Vector2d(img.width / 640.0, img.height / 480.0));
      l.b = l.b.cwiseProduct(Eigen::Vector2d(img.width / 640.0, img.height / 480.0));
    }
    auto& pipeline = pipelines[rec.camera];
    if (!pipeline) pipeline = std::make_unique<CameraPipeline>(rec.camera, geometry);
    pipeline->process(img, cm);
    const VisionResult vision = pipeline->visionResult();
    const calibration::ExtractionResult sample = calibration::extractSample(img, cm, eo, visionLines ? &vision.lines.lines : nullptr);

    nlohmann::json row;
    row["image"] = imagePath;
    row["camera"] = cameraName(rec.camera);
    row["calibration_sample"] = calibrationSampleJson(sample, eo.goalBoxDepth);
    nlohmann::json found = nlohmann::json::object();
    bool allFound = true;
    const LabelledLine* byRole[3] = {nullptr, nullptr, nullptr};
    for (int k = 0; k < 3; ++k)
      for (const auto& l : labels)
        if (l.name == kLabelNames[k]) byRole[k] = &l;
    std::array<ImageLine, 3> sl{};
    if (sample.sample) sl = sampleLines(*sample.sample);
    for (const auto& l : labels) {
      // The vision's line nearest to the label, if it is the same line at all (within 10 px and
      // 5 deg): a line found but measured beyond the tolerance is told from one not found.
      // Found: a line through the labelled paint (each labelled point within 3 px + half the
      // paint's width there, the direction within the same line's 5 deg); precisely: within
      // 3 px / 2 deg of the labelled points.
      const double tolA = kMaxDistancePx + paintWidthPx(cm, l, l.a, field.lineWidth) / 2;
      const double tolB = kMaxDistancePx + paintWidthPx(cm, l, l.b, field.lineWidth) / 2;
      std::optional<LabelOffset> nearest;
      bool v = false;
      for (const auto& f : vision.lines.lines) {
        const LabelOffset o = offsetFrom(f.imageFrom, f.imageTo, l);
        if (o.within(kSameLinePx, kSameLineDeg) && (!nearest || o.score() < nearest->score())) nearest = o;
        v = v || (o.angleDeg <= kSameLineDeg && o.aPx <= tolA && o.bPx <= tolB);
      }
      const bool precise = nearest && nearest->within(kMaxDistancePx, kMaxAngleDeg);
      bool s = false;
      if (sample.sample)
        for (int k = 0; k < 3; ++k) s = s || matches(sl[k].from, sl[k].to, l);
      found[l.name] = {{"vision", v}, {"vision_precise", precise}, {"paint_tolerance_px", {tolA, tolB}}, {"sample", s}};
      auto offsetJson = [](const std::optional<LabelOffset>& o) {
        return o ? nlohmann::json{{"angle_deg", o->angleDeg}, {"a_px", o->aPx}, {"b_px", o->bPx}} : nlohmann::json(nullptr);
      };
      found[l.name]["vision_nearest"] = offsetJson(nearest);
      ++labelled[l.name];
      byVision[l.name] += v;
      byVisionPrecise[l.name] += precise;
      bySample[l.name] += s;
      allFound = allFound && v;
    }
    row["labels_found"] = found;
    // The sample's lines are the labelled ones: short = connecting line, long ones = the other two.
    std::string verdict = "refused";
    const bool complete = byRole[0] && byRole[1] && byRole[2];
    labelledFrames += complete;
    if (sample.sample) {
      ++accepted;
      if (complete) {
        if (sampleIs(sl, byRole, kMaxDistancePx, kMaxAngleDeg)) {
          verdict = "labelled lines";
          ++right;
        } else if (sampleIs(sl, byRole, kSameLinePx, kSameLineDeg)) {
          verdict = "labelled lines, imprecise";
          ++imprecise;
        } else {
          verdict = "other lines";
          ++wrong;
        }
      } else {
        verdict = "unlabelled";
      }
      const auto& res = row["calibration_sample"]["residuals"];
      if (res.is_object()) {
        sampleAngles.push_back(std::abs(res["right_angle1_deg"].get<double>()));
        sampleAngles.push_back(std::abs(res["right_angle2_deg"].get<double>()));
        sampleParallel.push_back(std::abs(res["parallel_deg"].get<double>()));
      }
    } else {
      ++reasons[sample.reason.substr(0, sample.reason.find(':'))];
    }
    row["sample_verdict"] = verdict;
    // The labelled lines' own angles on the ground with the recorded matrix: what the matrix's
    // error alone gives (the floor under the sample's residuals).
    if (complete) {
      auto ground = [&](const LabelledLine& l) -> std::optional<Eigen::Vector2d> {
        const auto a = cm.pixelToGround(l.a), b = cm.pixelToGround(l.b);
        if (!a || !b) return std::nullopt;
        return (*b - *a).normalized();
      };
      const auto s = ground(*byRole[0]), g1 = ground(*byRole[1]), g2 = ground(*byRole[2]);
      if (s && g1 && g2) {
        const double a1 = std::asin(std::min(1.0, std::abs(s->dot(*g1)))) * 180 / M_PI;
        const double a2 = std::asin(std::min(1.0, std::abs(s->dot(*g2)))) * 180 / M_PI;
        labelAngles.push_back(a1);
        labelAngles.push_back(a2);
        row["label_right_angles_deg"] = {a1, a2};
      }
    }
    rows.push_back(row);

    const bool failure = !allFound || verdict != "labelled lines";
    if (failure && !options.failures.empty()) {
      // Left: the vision's result; right: the sample extraction's segments and result; the
      // labels on both.
      cv::Mat visionSide = annotateVision(sim::rgbFromCameraImage(img), vision, cm, 1);
      cv::Mat sampleSide = sim::rgbFromCameraImage(img);
      drawLabelledLines(visionSide, labels, 1);
      drawLabelledLines(sampleSide, labels, 1);
      drawSample(sampleSide, sample, 1);
      cv::Mat picture;
      cv::hconcat(visionSide, sampleSide, picture);
      sim::writePng((fs::path(options.failures) / (fs::path(imagePath).stem().string() + ".png")).string(), picture);
    }
    progress("eval real", i + 1, frames.size());
  }

  const int n = static_cast<int>(frames.size());
  nlohmann::json labels = nlohmann::json::object();
  for (const auto& [name, count] : labelled)
    labels[name] = {{"labelled", count},
                    {"found_by_vision", byVision[name]},
                    {"vision_rate", static_cast<double>(byVision[name]) / count},
                    {"found_by_vision_precise", byVisionPrecise[name]},
                    {"vision_precise_rate", static_cast<double>(byVisionPrecise[name]) / count},
                    {"found_by_sample", bySample[name]},
                    {"sample_rate", static_cast<double>(bySample[name]) / count}};
  nlohmann::json j;
  j["dir"] = options.dir;
  j["sample_lines"] = eo.source == calibration::LineSource::Lsd      ? "lsd"
                     : eo.source == calibration::LineSource::Vision ? "vision"
                                                                    : "lsd+vision";
  j["images"] = n;
  j["match"] = {{"found", "each labelled point within max_distance_px + half the paint's imaged width of the line, within same_line_deg"},
                {"precise", "each labelled point within max_distance_px of the line, within max_angle_deg"},
                {"max_distance_px", kMaxDistancePx},
                {"max_angle_deg", kMaxAngleDeg},
                {"same_line_px", kSameLinePx},
                {"same_line_deg", kSameLineDeg}};
  j["calibration_samples"] = {{"accepted", accepted},
                              {"accepted_rate", static_cast<double>(accepted) / n},
                              {"labelled_lines", right},
                              {"labelled_lines_imprecise", imprecise},
                              {"other_lines", wrong},
                              {"images_with_all_three_labels", labelledFrames},
                              {"refusals", reasons}};
  j["labels"] = labels;
  j["ground_angles_deg"] = {{"sample_right_angle_median", numberOrNull(median(sampleAngles))},
                            {"sample_parallel_median", numberOrNull(median(sampleParallel))},
                            {"labels_right_angle_median", numberOrNull(median(labelAngles))}};
  j["frames"] = rows;
  std::cerr << "eval real: " << accepted << " of " << n << " images gave a calibration sample (" << right
            << " with the labelled lines, " << imprecise << " with them beyond 3 px or 2 deg, " << wrong
            << " with other lines)\n";
  for (const auto& [name, count] : labelled)
    std::cerr << "  " << name << ": found by the vision in " << byVision[name] << " of " << count << " ("
              << byVisionPrecise[name] << " within 3 px and 2 deg of the labels), by the sample in " << bySample[name]
              << "\n";
  for (const auto& [reason, count] : reasons) std::cerr << "  refused " << count << "x: " << reason << "\n";
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
