// nao-soccer calibration-challenge: the whole Autonomous Calibration Challenge in the simulator
// (scenarios/CalibrationChallenge.h), the robot program playing both phases, scored as the
// referee scores.
#include <cmath>
#include <vector>
#include <cstdio>
#include <random>

#include <unistd.h>

#include <opencv2/imgproc.hpp>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/Rows.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "robot/OutputFiles.h"
#include "scenarios/CalibrationChallenge.h"
#include "scenarios/ChallengeEval.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"

namespace nao::cli {
namespace {

// The run from above: the true path (light blue), the believed one (yellow), phase 2's balls,
// each report (magenta cross, numbered by task) against its truth (white cross). A placement
// by the referee breaks the paths.
void writeFieldPicture(const std::string& path, const FieldDimensions& dims, const sim::ChallengeResult& r) {
  const FieldModel field = FieldModel::from(dims);
  std::vector<Eigen::Vector3d> balls;
  for (const Eigen::Vector2d& b : r.phaseTwoBalls) balls.emplace_back(b.x(), b.y(), 0.05);
  cv::Mat view = sim::drawFieldView(field, {}, balls);
  std::vector<Eigen::Vector2d> truth, belief;
  const Eigen::Vector2d gap = Eigen::Vector2d::Constant(NAN);
  for (std::size_t i = 0; i < r.track.size(); ++i) {
    const auto& t = r.track[i];
    if (i > 0 && (t.truth - r.track[i - 1].truth).head<2>().norm() > 0.3) {
      truth.push_back(gap);
      belief.push_back(gap);
    }
    truth.push_back(t.truth.head<2>());
    belief.push_back(t.beliefValid ? Eigen::Vector2d(t.belief.head<2>()) : gap);
  }
  sim::drawPath(view, field, belief, cv::Scalar(255, 230, 0));
  sim::drawPath(view, field, truth, cv::Scalar(120, 180, 255));
  int k = 1;
  for (const auto& t : r.tasks) {
    sim::drawMarker(view, field, t.truth, cv::Scalar(255, 255, 255), "");
    if (t.reported) sim::drawMarker(view, field, *t.reported, cv::Scalar(255, 60, 200), std::to_string(k));
    ++k;
  }
  cv::putText(view, "true path (blue), believed (yellow); reports (magenta, by task) against the truth (white)",
              cv::Point(8, view.rows - 10), cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  sim::writePng(path, view);
}

}  // namespace

int challengeCommand(const ChallengeCommandOptions& options) {
  sim::ChallengeOptions o;
  sim::CalibrationRunOptions& run = o.run;
  run.field = calibrationFieldFrom(options.common);
  run.robotModel = options.sim.model;
  checkRobotModel(run.robotModel, run.field);
  run.lighting = lightingFrom(options.sim.lighting);
  run.seed = options.common.seed;
  // What the options leave open, the seed decides, as for a trial of eval challenge with this seed.
  const sim::ChallengeDraw draw = sim::challengeDraw(run.seed, options.maxOffset);
  run.miscalibration = options.sim.miscalibration == "random" ? draw.offsets : miscalibrationFrom(options.sim, run.seed);
  run.side = options.start == "seed" ? draw.side : options.start == "left" ? 1 : -1;
  run.randomize = options.randomize;
  run.timeLimit = options.timeLimit;
  run.imagesDir = options.images;
  run.recordPath = options.record;
  o.skipCalibration = options.skipCalibration;
  if (options.venue != "none") {
    const std::vector<sim::Venue> venues = sim::loadVenues(dataPath("config/venues.json"), run.field);
    const sim::Venue& venue =
        options.venue == "random" ? venues[run.seed % venues.size()] : sim::venueNamed(venues, options.venue);
    o.venue = venue.name;
    o.phaseTwoBalls = venue.balls;
    run.floorFriction = venue.floorFriction;
    run.venue = venue.look;
  }
  DebugSink debug(options.debug);
  run.debug = debug.channels();
  const std::size_t limit = static_cast<std::size_t>(run.timeLimit);
  o.progress = [limit](int phase, double t) {
    progress(phase == 1 ? "calibration-challenge: phase 1 (calibration), simulated s"
                        : "calibration-challenge: phase 2 (evaluation), simulated s",
             static_cast<std::size_t>(t), limit);
  };

  const sim::ChallengeResult r = sim::runChallenge(o);
  if (isatty(fileno(stderr))) std::fputc('\n', stderr);
  nlohmann::json j = sim::challengeJson(o, r);
  if (!options.images.empty()) {
    io::makeDirectories(options.images);
    writeFieldPicture(options.images + "/field.png", run.field, r);
  }
  nlohmann::json files = r.imagesWritten;
  if (!options.images.empty()) files.push_back(options.images + "/field.png");
  char calibration[64];
  std::snprintf(calibration, sizeof calibration, r.calibrationSkipped ? "skipped" : "%.1f s", r.calibrationSeconds);
  std::fprintf(stderr, "calibration-challenge: %s; calibration %s, evaluation %.1f s, %d falls\n",
               r.terminated.empty() ? "finished" : ("TERMINATED (" + r.terminated + ")").c_str(), calibration,
               r.evaluationSeconds, r.falls);
  for (const auto& t : r.tasks)
    std::fprintf(stderr, "  %-18s %-28s error %s  (%.1f s)\n", t.task.c_str(), ("\"" + t.said + "\"").c_str(),
                 t.error ? (std::to_string(*t.error) + " m").c_str() : "none", t.simSeconds);
  j["files"] = files;
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return r.terminated.empty() && r.tasks.size() == 5 ? 0 : 1;
}

// eval challenge: --trials N seeded challenges, one row each (--rows FILE: resumable).
int evalChallengeCommand(const EvalChallengeOptions& options) {
  sim::ChallengeEvalOptions o;
  o.field = calibrationFieldFrom(options.common);
  o.robotModel = options.model;
  checkRobotModel(o.robotModel, o.field);
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.seeds = options.seeds;
  o.lightings = lightingsFrom(options.lighting);
  o.randomize = options.randomize;
  o.skipCalibration = options.skipCalibration;
  o.maxOffsetDeg = options.maxOffset;
  o.timeLimit = options.timeLimit;
  if (options.venue == "random") o.venues = sim::loadVenues(dataPath("config/venues.json"), o.field);
  else if (options.venue != "none")
    o.venues = {sim::venueNamed(sim::loadVenues(dataPath("config/venues.json"), o.field), options.venue)};
  o.progress = [](const nlohmann::json& row, int done, int total) {
    std::string errors;
    for (const auto& t : row["tasks"]) {
      char e[32];
      std::snprintf(e, sizeof e, " %.3f", t["error_m"].is_null() ? NAN : t["error_m"].get<double>());
      errors += e;
    }
    std::fprintf(stderr, "eval challenge: trial %d/%d seed %llu (%s): %s; errors (m)%s; %.0f s wall\n", done, total,
                 row.at("seed").get<unsigned long long>(), row.at("lighting").get<std::string>().c_str(),
                 row["failure"].is_null() ? "ok" : row["failure"].get<std::string>().c_str(), errors.c_str(),
                 row.at("wall_s").get<double>());
  };
  std::vector<nlohmann::json> rows;
  if (!options.rows.empty()) rows = readRows(options.rows, "eval challenge");
  RowWriter writeRow(options.rows);
  nlohmann::json j = sim::evalChallenge(o, rows, [&](const nlohmann::json& row) { writeRow(row); });
  j["seed"] = o.seed;
  if (!o.seeds.empty()) j["seed_list"] = o.seeds;
  std::fprintf(stderr, "eval challenge: %d trials, %zu failed, terminations %s; every report within 0.05 m in %.0f %% of the trials\n",
               j["trials"].get<int>(), j["failures"].size(), j["terminations"].dump().c_str(), 100 * j["within_0_05_m"].get<double>());
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return 0;
}

}  // namespace nao::cli
