// nao-soccer run: the robot program on a backend.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "scenarios/SimRun.h"
#include "sim/ImageIO.h"

namespace nao::cli {

namespace {

// --cameras files:DIR's decoder (run in FileCamera's thread). Not sim::readImage: that keeps
// libpng's warnings off the terminal by pointing fd 2 elsewhere while it decodes, for the whole
// process, which would swallow the other threads' log lines.
CameraImage decodeCameraFile(const std::string& path, CameraId camera) {
  std::ifstream f(path, std::ios::binary);
  const std::vector<uchar> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  cv::Mat bgr;
  try {
    if (!bytes.empty()) bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw Error(path, "not a readable PNG or JPEG image: " + e.err);
  }
  if (bgr.empty() || bgr.cols < 2) throw Error(path, "not a readable PNG or JPEG image");
  if (bgr.cols % 2 != 0) bgr = bgr.colRange(0, bgr.cols - 1).clone();  // YUYV pairs
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return sim::cameraImageFromRgb(rgb, camera);
}

}  // namespace

int runCommand(const RunOptions& options) {
  if (options.backend == "nao")
    return runNao(options, decodeCameraFile);

  sim::SimRunOptions o;
  o.field = fieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.seconds = options.seconds;
  const auto& p = options.pose;
  if (!p.empty()) o.pose = Eigen::Vector3d(p[0], p[1], p[2] * M_PI / 180);
  else o.pose = Eigen::Vector3d(-(o.field.length / 2 - o.field.penaltyCrossDistance), -o.field.width / 2, M_PI / 2);
  o.cameras = options.cameras != "off";
  o.lighting = lightingFrom(options.sim.lighting);
  o.miscalibration = miscalibrationFrom(options.sim, options.common.seed);
  o.imagesDir = options.images;
  o.seed = options.common.seed;
  o.progress = [&](double t) { progress("run: simulated seconds", static_cast<std::size_t>(t + 0.5), static_cast<std::size_t>(o.seconds + 0.5)); };

  const sim::SimRunResult r = sim::runSim(o);
  std::fprintf(stderr,
               "run: %.1f s simulated in %.1f s (%.2fx real time), %llu cycles, %d top + %d bottom images, "
               "torso height %.3f..%.3f m, %s\n",
               r.simSeconds, r.wallSeconds, r.simSeconds / std::max(r.wallSeconds, 1e-9),
               static_cast<unsigned long long>(r.cycles), r.imagesTop, r.imagesBottom, r.torsoHeightMin,
               r.torsoHeightMax, r.fell ? "FELL" : "no fall");
  // The JSON holds results only (no wall-clock figures: `bench sim` measures speed), so the
  // same --seed gives the same bytes.
  if (!options.common.json.empty()) {
    nlohmann::json j = {{"backend", options.backend},
                        {"sim_seconds", r.simSeconds},
                        {"cycles", r.cycles},
                        {"images", {{"top", r.imagesTop}, {"bottom", r.imagesBottom}}},
                        {"images_processed", {{"top", r.imagesProcessedTop}, {"bottom", r.imagesProcessedBottom}}},
                        {"fell", r.fell},
                        {"torso_height_m", {{"min", r.torsoHeightMin}, {"max", r.torsoHeightMax}}},
                        {"final_pose", {r.finalPose.x(), r.finalPose.y(), r.finalPose.z() * 180 / M_PI}},
                        {"modules", r.moduleOrder},
                        {"files", r.imagesWritten},
                        {"miscalibration_deg", calibrationDegJson(o.miscalibration)},
                        {"lighting", lightingJson(o.lighting)},
                        {"seed", o.seed}};
    writeJson(options.common.json, j);
  }
  return r.fell ? 1 : 0;
}

}  // namespace nao::cli
