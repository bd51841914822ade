// nao-soccer perceive: the vision pipeline and the calibration's sample extraction on one
// PNG/JPEG or raw YUV422 image. The camera matrix is the one recorded with the image
// (--camera-matrix), or that of a NAO standing with the given head and torso angles (default
// 0), nominal calibration, the intrinsics following the image's size with the NAO's field of
// view.
#include <cmath>
#include <iostream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SampleReport.h"
#include "apps/SimOptions.h"
#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/RecordedCameraMatrix.h"
#include "perception/calibration/SampleExtraction.h"
#include "perception/vision/Annotate.h"
#include "perception/vision/CameraPipeline.h"
#include "perception/vision/VisionPipeline.h"
#include "representations/perception/DenoisedImage.h"
#include "robot/Error.h"
#include "sim/ImageIO.h"

namespace nao::cli {
namespace {

nlohmann::json vec(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }

const char* className(RegionClass c) {
  switch (c) {
    case RegionClass::Field: return "field";
    case RegionClass::White: return "white";
    case RegionClass::Other: return "other";
    default: return "unknown";
  }
}

nlohmann::json resultJson(const VisionResult& r, const CameraImage& img, const std::string& path) {
  nlohmann::json j;
  j["image"] = {{"path", path}, {"width", img.width}, {"height", img.height}, {"camera", cameraName(img.camera)}};
  const FieldColour& fc = r.regions.fieldColour;
  j["field_colour"] = {{"valid", fc.valid}, {"hue_min", fc.hueMin}, {"hue_max", fc.hueMax}, {"sat_min", fc.satMin},
                       {"y_min", fc.yMin},  {"y_max", fc.yMax},    {"mean_y", fc.meanY},   {"mean_s", fc.meanS}};
  // The sensor's clipping level where wide areas are clipped (their regions are "unknown").
  j["saturation_level"] = r.regions.saturationLevel >= 0 ? nlohmann::json(r.regions.saturationLevel) : nlohmann::json();
  std::map<std::string, int> counts;
  for (const auto* lines : {&r.regions.vertical, &r.regions.horizontal})
    for (const auto& sl : *lines)
      for (const auto& reg : sl.regions) counts[className(reg.cls)] += 1;
  j["regions"] = {{"vertical_scan_lines", r.regions.vertical.size()},
                  {"horizontal_scan_lines", r.regions.horizontal.size()},
                  {"by_class", counts}};
  nlohmann::json boundary = nlohmann::json::array();
  for (const auto& p : r.boundary.points) boundary.push_back(vec(p));
  j["field_boundary"] = {{"valid", r.boundary.valid}, {"points", boundary}};
  nlohmann::json obstacles = nlohmann::json::array();
  for (const auto& o : r.obstacles.obstacles)
    obstacles.push_back({{"box", {o.left, o.top, o.right, o.bottom}}, {"foot_robot", vec(o.footRobot)}});
  j["obstacles"] = obstacles;
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& l : r.lines.lines) {
    nlohmann::json spots = nlohmann::json::array();
    for (const auto& s : l.spots) spots.push_back(vec(s));
    lines.push_back({{"image", {vec(l.imageFrom), vec(l.imageTo)}}, {"robot", {vec(l.from), vec(l.to)}}, {"spots", spots}});
  }
  j["lines"] = lines;
  j["circle"] = {{"found", r.lines.circle.found}, {"centre_robot", vec(r.lines.circle.centre)}, {"radius", r.lines.circle.radius}};
  nlohmann::json xs = nlohmann::json::array();
  for (const auto& x : r.lines.intersections) {
    const char* t = x.type == LinesPercept::Intersection::Type::L ? "L" : x.type == LinesPercept::Intersection::Type::T ? "T" : "X";
    xs.push_back({{"type", t}, {"robot", vec(x.position)}, {"image", vec(x.image)}, {"lines", {x.line1, x.line2}}});
  }
  j["intersections"] = xs;
  j["penalty_mark"] = r.lines.penaltyMark ? nlohmann::json{{"robot", vec(*r.lines.penaltyMark)}, {"image", vec(r.penaltyMarkImage)}}
                                          : nlohmann::json(nullptr);
  const auto& g = r.lines.goalBoxSide;
  j["goal_box_side"] = {{"found", g.found}, {"short_line", g.shortLine}, {"long_lines", {g.longLine1, g.longLine2}}};
  const BallPercept& b = r.ball;
  j["ball"] = {{"seen", b.seen},
               {"image", vec(b.image)},
               {"radius_px", b.radiusPx},
               {"robot", vec(b.position)},
               {"covariance", {{b.covariance(0, 0), b.covariance(0, 1)}, {b.covariance(1, 0), b.covariance(1, 1)}}},
               {"confidence", b.confidence}};
  j["stage_ms"] = r.stageMs;
  return j;
}

}  // namespace

int perceiveCommand(const PerceiveOptions& options) {
  const std::string& path = options.image;
  CameraId camera = options.camera == "top" ? CameraId::Top : CameraId::Bottom;
  const auto head = options.head.empty() ? std::vector<double>{0, 0} : options.head;
  const auto torso = options.torso.empty() ? std::vector<double>{0, 0} : options.torso;
  const int scale = options.scale;
  const FieldDimensions field = fieldFrom(options.common);
  const VisionGeometry geometry = VisionGeometry::from(field);

  std::optional<RecordedCameraMatrix> recorded;
  if (!options.cameraMatrix.empty()) {
    recorded = RecordedCameraMatrix::read(options.cameraMatrix);
    camera = recordedCamera(*recorded, options.cameraMatrix, camera, options.common.has("--camera"));
  }
  const CameraImage img = sim::readImage(path, options.width, options.height, camera);
  requireNaoImageSize(img, path);
  JointArray joints = StandController::standPosture();
  joints[HeadYaw] = head[0] * M_PI / 180;
  joints[HeadPitch] = head[1] * M_PI / 180;
  const Eigen::Vector2d imu = Eigen::Vector2d(torso[0], torso[1]) * M_PI / 180;
  const CameraMatrix cm =
      recorded ? recorded->forImage(img.width, img.height)
               : computeCameraMatrix(joints, imu, camera, CameraCalibration{}, CameraIntrinsics::fromFovY(img.width, img.height));
  DebugSink debug(options.debug);
  CameraPipelineConfig pipelineConfig;
  pipelineConfig.debug = debug.channels();
  CameraPipeline pipeline(camera, geometry, pipelineConfig);
  pipeline.process(img, cm);
  const VisionResult r = pipeline.visionResult();

  // The calibration's sample extraction with this camera matrix, as the robot program runs it.
  const calibration::ExtractionOptions eo = robotExtractionOptions(field);
  const auto* visionLines = eo.source != calibration::LineSource::Lsd ? &r.lines.lines : nullptr;
  const calibration::ExtractionResult sample = recorded ? calibration::extractSample(img, cm, eo, visionLines)
                                                        : calibration::extractSample(img, joints, imu, cm.intrinsics, {}, eo, visionLines);

  if (!options.out.empty()) {
    cv::Mat picture = annotateVision(sim::rgbFromCameraImage(img), r, cm, scale);
    if (recorded) drawLabelledLines(picture, recorded->lines, scale);
    drawSample(picture, sample, scale);
    sim::writePng(options.out, picture);
  }
  nlohmann::json j = resultJson(r, img, path);
  j["camera_matrix"] = recorded ? nlohmann::json(options.cameraMatrix) : nlohmann::json("nominal");
  j["head_deg"] = recorded ? nlohmann::json(nullptr) : nlohmann::json{head[0], head[1]};
  j["torso_deg"] = recorded ? nlohmann::json(nullptr) : nlohmann::json{torso[0], torso[1]};
  const DenoisedImage& denoised = pipeline.get<DenoisedImage>();
  j["image"]["noise"] = denoised.noise;
  j["image"]["blur_radius"] = denoised.radius;  // 0: the vision read the image as it came
  j["calibration_sample"] = calibrationSampleJson(sample, eo.goalBoxDepth);
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
