#include "apps/SampleReport.h"

#include <opencv2/imgproc.hpp>

#include "controllers/RobotProgram.h"
#include "controllers/modules/Calibrator.h"
#include "perception/calibration/CalibrationCost.h"
#include "robot/Error.h"

namespace nao::cli {
namespace {

nlohmann::json point(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
nlohmann::json line(const ImageLine& l) { return {point(l.from), point(l.to)}; }

cv::Point px(const Eigen::Vector2d& p, int scale) {
  return {static_cast<int>(std::lround(p.x() * scale)), static_cast<int>(std::lround(p.y() * scale))};
}

void drawSegment(cv::Mat& rgb, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const cv::Scalar& colour, int scale,
                 int thickness = 1) {
  cv::line(rgb, px(a, scale), px(b, scale), colour, thickness * scale, cv::LINE_AA);
}

}  // namespace

CameraId recordedCamera(const RecordedCameraMatrix& recorded, const std::string& file, CameraId asked, bool askedGiven) {
  if (askedGiven && recorded.camera != asked)
    throw Error("--camera", std::string(cameraName(asked)) + ", but " + file + " is of the " +
                                cameraName(recorded.camera) + " camera");
  return recorded.camera;
}

void requireNaoImageSize(const CameraImage& image, const std::string& path) {
  if (!((image.width == 640 && image.height == 480) || (image.width == 320 && image.height == 240)))
    throw Error(path, "image size: " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                          " is not a NAO camera's (640x480 or 320x240)");
}

calibration::ExtractionOptions robotExtractionOptions(const FieldDimensions& field) {
  const auto calibrator = loadParams<modules::Calibrator::Params>("Calibrator", RobotProgramConfig::defaultConfigDir());
  calibration::ExtractionOptions eo;
  eo.source = calibration::lineSourceFromName(calibrator.lines, "Calibrator.lines");
  if (field.hasGoalBox) eo.goalBoxDepth = field.goalBoxAreaLength;
  eo.lineWidth = field.lineWidth;
  return eo;
}

std::array<ImageLine, 3> sampleLines(const calibration::CalibrationSample& sample) {
  return {sample.lines[0].centre(), sample.lines[1].centre(), sample.lines[2].centre()};
}

nlohmann::json calibrationSampleJson(const calibration::ExtractionResult& result, double goalBoxDepth) {
  nlohmann::json j;
  j["accepted"] = result.sample.has_value();
  j["reason"] = result.sample ? nlohmann::json(nullptr) : nlohmann::json(result.reason);
  j["source"] = result.source.empty() ? nlohmann::json(nullptr) : nlohmann::json(result.source);
  if (!result.sample) {
    j["lines"] = nullptr;
    j["residuals"] = nullptr;
    return j;
  }
  const auto& s = *result.sample;
  nlohmann::json lines = nlohmann::json::object();
  for (int l = 0; l < 3; ++l)
    lines[calibration::kLineRoleNames[l]] = {{"image", line(s.lines[l].centre())},
                                             {"edges", {line(s.lines[l].edgeA), line(s.lines[l].edgeB)}},
                                             {"rms_px", s.lines[l].rmsPx}};
  j["lines"] = lines;
  calibration::CostOptions co;
  co.goalBoxDepth = goalBoxDepth;
  const calibration::CalibrationCost cost({s}, co);
  const auto r = cost.sampleResiduals({0, 0, 0, 0, 0, 0}, 0);
  j["residuals"] = r.projected ? nlohmann::json{{"right_angle1_deg", r.angle1Deg},
                                                {"right_angle2_deg", r.angle2Deg},
                                                {"parallel_deg", r.parallelDeg},
                                                {"depth_m", r.depthErrorM + goalBoxDepth}}
                               : nlohmann::json(nullptr);
  return j;
}

void drawLabelledLines(cv::Mat& rgb, const std::vector<LabelledLine>& lines, int scale) {
  const cv::Scalar magenta(255, 0, 255);
  for (const auto& l : lines) {
    // Extended across the image: the labels are two points on the line, not its ends.
    const Eigen::Vector2d d = (l.b - l.a).normalized();
    const double reach = 2.0 * (rgb.cols + rgb.rows) / scale;
    drawSegment(rgb, l.a - reach * d, l.b + reach * d, magenta, scale);
    for (const auto& p : {l.a, l.b}) cv::circle(rgb, px(p, scale), 3 * scale, magenta, cv::FILLED, cv::LINE_AA);
  }
}

void drawSample(cv::Mat& rgb, const calibration::ExtractionResult& result, int scale) {
  if (result.sample) {
    const auto lines = sampleLines(*result.sample);
    for (int l = 0; l < 3; ++l)
      drawSegment(rgb, lines[l].from, lines[l].to, l == 0 ? cv::Scalar(255, 40, 40) : cv::Scalar(255, 160, 0), scale, 2);
    return;
  }
  for (const auto& s : result.segments) drawSegment(rgb, s.from, s.to, cv::Scalar(0, 200, 255), scale);
  if (result.detection.found)
    for (const auto* s : {&result.detection.shortLine, &result.detection.longLine1, &result.detection.longLine2})
      drawSegment(rgb, s->from, s->to, cv::Scalar(160, 160, 160), scale, 2);
  const std::string text = "no calibration sample: " + result.reason;
  cv::putText(rgb, text, cv::Point(4 * scale, rgb.rows - 6 * scale), cv::FONT_HERSHEY_SIMPLEX, 0.4 * scale,
              cv::Scalar(0, 0, 0), 3 * scale, cv::LINE_AA);
  cv::putText(rgb, text, cv::Point(4 * scale, rgb.rows - 6 * scale), cv::FONT_HERSHEY_SIMPLEX, 0.4 * scale,
              cv::Scalar(255, 255, 255), scale, cv::LINE_AA);
}

}  // namespace nao::cli
