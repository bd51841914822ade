// nao-soccer run: the robot program on a backend.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "scenarios/SimRun.h"

namespace nao::cli {

int runCommand(const RunOptions& options) {
  if (options.backend == "nao")
    return runNao(options);

  sim::SimRunOptions o;
  o.field = fieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.venue = venueFrom(options.sim.venue).forSeed(options.common.seed);
  o.seconds = options.seconds;
  const auto& p = options.pose;
  if (!p.empty()) o.pose = Eigen::Vector3d(p[0], p[1], p[2] * M_PI / 180);
  else o.pose = Eigen::Vector3d(-(o.field.length / 2 - o.field.penaltyCrossDistance), -o.field.width / 2, M_PI / 2);
  o.cameras = options.cameras != "off";
  o.lighting = lightingFrom(options.sim.lighting);
  o.miscalibration = miscalibrationFrom(options.sim, options.common.seed);
  o.imagesDir = options.images;
  if (const auto& g = options.goTo; g.size() == 3) o.goTo = Pose2(g[0], g[1], g[2] * M_PI / 180);
  if (const auto& b = options.ball; b.size() == 2) o.ball = Eigen::Vector2d(b[0], b[1]);
  o.seed = options.common.seed;
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  o.progress = [&](double t) { progress("run: simulated seconds", static_cast<std::size_t>(t + 0.5), static_cast<std::size_t>(o.seconds + 0.5)); };

  const sim::SimRunResult r = sim::runSim(o);
  auto percentile = [](std::vector<double> v, double q) {
    if (v.empty()) return -1.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
  };
  auto degrees = [](std::vector<double> v) {
    for (double& x : v) x *= 180 / M_PI;
    return v;
  };
  auto poseJson = [](const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z() * 180 / M_PI}); };
  const Eigen::Vector3d estimated(r.finalEstimate.pose.x, r.finalEstimate.pose.y, r.finalEstimate.pose.theta);
  if (!r.positionErrors.empty())
    std::fprintf(stderr, "run: localization error median %.3f m, p95 %.3f m; heading median %.2f deg; valid %.0f %% of the images\n",
                 percentile(r.positionErrors, 0.5), percentile(r.positionErrors, 0.95),
                 percentile(degrees(r.headingErrors), 0.5),
                 100.0 * static_cast<double>(r.validRuns) / std::max<long>(1, r.cognitionRunsTotal));
  std::fprintf(stderr, "run: wall time per motion cycle median %.3f ms, p99 %.3f ms; per cognition run median %.2f ms, p95 %.2f ms\n",
               percentile(r.motionMs, 0.5), percentile(r.motionMs, 0.99), percentile(r.cognitionMs, 0.5),
               percentile(r.cognitionMs, 0.95));
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
                        {"cadences", {{"motion", r.motionModules}, {"cognition", r.cognitionModules}}},
                        {"cognition_hz", {{"top", r.imagesProcessedTop / std::max(r.simSeconds, 1e-9)},
                                          {"bottom", r.imagesProcessedBottom / std::max(r.simSeconds, 1e-9)}}},
                        {"localization_error_m", {{"median", percentile(r.positionErrors, 0.5)},
                                                  {"p95", percentile(r.positionErrors, 0.95)},
                                                  {"max", percentile(r.positionErrors, 1.0)}}},
                        {"heading_error_deg", {{"median", percentile(degrees(r.headingErrors), 0.5)},
                                               {"p95", percentile(degrees(r.headingErrors), 0.95)}}},
                        {"localization_valid_fraction",
                         static_cast<double>(r.validRuns) / std::max<long>(1, r.cognitionRunsTotal)},
                        {"ball_error_m", {{"median", percentile(r.ballErrors, 0.5)}, {"p95", percentile(r.ballErrors, 0.95)}}},
                        {"final_true_pose", poseJson(r.finalPose)},
                        {"final_estimated_pose", poseJson(estimated)},
                        {"final_estimate_valid", r.finalEstimate.valid},
                        {"files", r.imagesWritten},
                        {"miscalibration_deg", calibrationDegJson(o.miscalibration)},
                        {"lighting", lightingJson(o.lighting)},
                        {"venue", sim::toJson(o.venue)},
                        {"seed", o.seed}};
    if (o.goTo) {
      const Eigen::Vector2d target(o.goTo->x, o.goTo->y);
      const double position = (r.finalPose.head<2>() - target).norm();
      const double heading = std::abs(Pose2::wrap(r.finalPose.z() - o.goTo->theta)) * 180 / M_PI;
      j["goto"] = {{"target", poseJson(Eigen::Vector3d(o.goTo->x, o.goTo->y, o.goTo->theta))},
                   {"position_error_m", position},
                   {"heading_error_deg", heading},
                   {"arrived", position <= 0.10 && heading <= 5.0}};
    }
    nlohmann::json seconds = nlohmann::json::array();
    for (const auto& s : r.seconds) {
      nlohmann::json e = {{"t", s.t},
                          {"true_pose", poseJson(s.truePose)},
                          {"estimated_pose", poseJson(Eigen::Vector3d(s.estimate.pose.x, s.estimate.pose.y, s.estimate.pose.theta))},
                          {"valid", s.estimate.valid},
                          {"sigma_m", s.estimate.sigmaTranslation()},
                          {"quality", s.estimate.quality},
                          {"position_error_m", s.positionError},
                          {"heading_error_deg", s.headingError < 0 ? -1.0 : s.headingError * 180 / M_PI}};
      if (s.trueBall) e["true_ball"] = {s.trueBall->x(), s.trueBall->y()};
      if (s.ball.valid) {
        e["ball"] = {{"position", {s.ball.position.x(), s.ball.position.y()}},
                     {"lost", s.ball.lost},
                     {"rolling", s.ball.rolling},
                     {"error_m", s.ballError}};
      }
      seconds.push_back(e);
    }
    j["per_second"] = seconds;
    writeJson(options.common.json, j);
  }
  return r.fell ? 1 : 0;
}

}  // namespace nao::cli
