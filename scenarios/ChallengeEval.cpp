#include "scenarios/ChallengeEval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "robot/Error.h"
#include "scenarios/EvalRows.h"
#include "scenarios/CalibrationChallenge.h"

namespace nao::sim {

namespace {

const Lighting& lightingOf(const ChallengeEvalOptions& o, std::uint64_t seed) { return o.lightings[seed % o.lightings.size()]; }

nlohmann::json stats(const std::vector<double>& v) {
  if (v.empty()) return {{"median", nullptr}, {"p95", nullptr}, {"max", nullptr}, {"n", 0}};
  return {{"median", quantile(v, 0.5)}, {"p95", quantile(v, 0.95)}, {"max", quantile(v, 1.0)}, {"n", v.size()}};
}

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

nlohmann::json challengeEvalSettings(const ChallengeEvalOptions& o) {
  nlohmann::json venues = nlohmann::json::array();
  for (const Venue& v : o.venues) venues.push_back(v.name);
  nlohmann::json lightings = nlohmann::json::array();
  for (const Lighting& l : o.lightings) lightings.push_back(l.name);
  return {{"randomize", o.randomize},
          {"skip_calibration", o.skipCalibration},
          {"max_offset_deg", o.maxOffsetDeg},
          {"time_limit_s", o.timeLimit},
          {"lightings", lightings},
          {"robot_model", o.robotModel},
          {"venues", venues},
          {"field", {{"length", o.field.length}, {"width", o.field.width}}}};
}

nlohmann::json runChallengeTrial(const ChallengeEvalOptions& o, std::uint64_t seed) {
  const auto wall0 = std::chrono::steady_clock::now();
  ChallengeOptions co;
  CalibrationRunOptions& run = co.run;
  run.field = o.field;
  run.robotModel = o.robotModel;
  const ChallengeDraw draw = challengeDraw(seed, o.maxOffsetDeg);
  run.miscalibration = draw.offsets;
  run.lighting = lightingOf(o, seed);
  run.side = draw.side;
  run.seed = seed;
  run.randomize = o.randomize;
  run.timeLimit = o.timeLimit;
  co.skipCalibration = o.skipCalibration;
  if (!o.venues.empty()) {
    const Venue& venue = o.venues[seed % o.venues.size()];
    co.venue = venue.name;
    co.phaseTwoBalls = venue.balls;
    run.floorFriction = venue.floorFriction;
    run.venue = venue.look;
  }
  const ChallengeResult r = runChallenge(co);
  nlohmann::json row = challengeJson(co, r);
  nlohmann::json termination;
  for (const ChallengeEvent& e : r.events)
    if (e.kind == "termination") termination = {{"t", e.t}, {"text", e.text}};
  row.erase("events");
  row.erase("track");  // a row per trial stays small; the replay command gives it
  row["termination_event"] = termination;
  row["settings"] = challengeEvalSettings(o);
  // The command that plays this trial alone.
  char maxOffset[32];
  std::snprintf(maxOffset, sizeof maxOffset, "%g", o.maxOffsetDeg);
  row["replay"] = "calibration-challenge --seed " + std::to_string(seed) + " --lighting " + run.lighting.name +
                  (co.venue.empty() ? "" : " --venue " + co.venue) + (o.maxOffsetDeg != 3 ? std::string(" --max-offset ") + maxOffset : "") +
                  (o.randomize ? " --randomize" : "") + (o.skipCalibration ? " --skip-calibration" : "") +
                  (o.timeLimit != 600 ? " --time-limit " + format("%g", o.timeLimit) : "");

  // Why the trial fails, if it does: the first reason found.
  std::string failure;
  if (!r.terminated.empty()) failure = "terminated: " + r.terminated;
  for (const ChallengeTaskResult& t : r.tasks) {
    if (!failure.empty()) break;
    if (!t.error) failure = t.task + ": no valid report (\"" + t.said + "\")";
    else if (*t.error > o.maxErrorM) failure = t.task + ": " + format("%.3f", *t.error) + " m off";
  }
  if (failure.empty() && r.tasks.size() < 5) failure = "only " + std::to_string(r.tasks.size()) + " tasks";
  if (failure.empty() && !o.skipCalibration)
    for (int k = 0; k < 6; ++k)
      if (std::abs(row["offsets"]["error_deg"][k].get<double>()) > o.maxOffsetErrorDeg) {
        failure = std::string(CameraCalibration::kNames[k]) + ": " + format("%.3f", row["offsets"]["error_deg"][k].get<double>()) +
                  " deg off";
        break;
      }
  row["failure"] = failure.empty() ? nlohmann::json() : nlohmann::json(failure);
  row["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return row;
}

nlohmann::json aggregateChallengeRows(std::vector<nlohmann::json> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a.at("seed").get<std::uint64_t>() < b.at("seed").get<std::uint64_t>(); });
  std::map<std::string, int> terminations;
  std::map<std::string, std::vector<double>> categories;
  std::vector<double> taskErrors, offsetErrors, calibration, evaluation;
  nlohmann::json failures = nlohmann::json::array();
  int within = 0, roundedZero = 0;
  for (const nlohmann::json& r : rows) {
    if (!r.at("terminated").is_null()) ++terminations[r.at("terminated").get<std::string>()];
    for (const auto& [name, v] : r.at("categories").items())
      if (!v.is_null()) categories[name].push_back(v.get<double>());
    bool allWithin = r.at("tasks").size() == 5, allZero = allWithin;
    for (const auto& t : r.at("tasks")) {
      if (t.at("error_m").is_null()) {
        allWithin = allZero = false;
        continue;
      }
      taskErrors.push_back(t.at("error_m").get<double>());
      allWithin = allWithin && t.at("error_m").get<double>() <= 0.05;
      allZero = allZero && t.at("error_rounded_m").get<double>() == 0.0;
    }
    within += allWithin && r.at("terminated").is_null();
    roundedZero += allZero && r.at("terminated").is_null();
    if (!r.at("settings").at("skip_calibration").get<bool>())
      for (const auto& e : r.at("offsets").at("error_deg")) offsetErrors.push_back(std::abs(e.get<double>()));
    const auto& phases = r.at("phases");
    if (phases.at("calibration").contains("sim_s")) calibration.push_back(phases.at("calibration").at("sim_s").get<double>());
    if (r.at("tasks").size() == 5) evaluation.push_back(phases.at("evaluation").at("sim_s").get<double>());
    if (!r.at("failure").is_null()) failures.push_back({{"seed", r.at("seed")}, {"reason", r.at("failure")}});
  }
  nlohmann::json cats = nlohmann::json::object();
  for (const auto& [name, v] : categories) cats[name] = stats(v);
  const double n = static_cast<double>(std::max<std::size_t>(rows.size(), 1));
  nlohmann::json j = {{"trials", rows.size()},
                      {"terminations", terminations},
                      {"categories", cats},
                      {"task_error_m", stats(taskErrors)},
                      {"offsets_error_deg", stats(offsetErrors)},
                      {"phase_s", {{"calibration", stats(calibration)}, {"evaluation", stats(evaluation)}}},
                      {"within_0_05_m", within / n},
                      {"rounded_zero", roundedZero / n},
                      {"failures", failures}};
  if (!rows.empty()) j["settings"] = rows.front().at("settings");
  return j;
}

nlohmann::json evalChallenge(const ChallengeEvalOptions& o, std::vector<nlohmann::json> rows,
                             const std::function<void(const nlohmann::json& row)>& onRow) {
  const std::vector<std::uint64_t> seeds = trialSeeds(o.seed, o.trials, o.seeds, "--trials");
  if (o.lightings.empty()) throw Error("--lighting", "no lighting");
  const nlohmann::json settings = challengeEvalSettings(o);
  return aggregateChallengeRows(collectRows(
      seeds, rowsBySeed(std::move(rows), settings), [&](std::uint64_t seed) { return runChallengeTrial(o, seed); }, onRow,
      o.progress));
}

}  // namespace nao::sim
