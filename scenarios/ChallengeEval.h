#pragma once
// Many seeded calibration challenges (scenarios/CalibrationChallenge.h): trial i has the seed
// `seed + i`, and everything in it follows from that seed (the offsets, up to +-maxOffsetDeg per
// parameter; the start side; the balls; the foreign robot with `randomize`), the lighting
// preset too (the seed's turn through the list). Each trial becomes one row (JSON), so an
// interrupted evaluation resumes from its rows and a batch engine can split it by seeds; the
// aggregate is computed from the rows alone, sorted by seed, so a resumed or split run and an
// uninterrupted one agree to the bit. Any failure names its seed: `calibration-challenge --seed
// S` with the row's settings runs it again.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "scenarios/Venue.h"
#include "sim/Lighting.h"

namespace nao::sim {

struct ChallengeEvalOptions {
  FieldDimensions field;
  std::string robotModel;
  int trials = 100;
  std::uint64_t seed = 1;
  std::vector<std::uint64_t> seeds;  // not empty: exactly these trials (trials and seed aside)
  std::vector<Lighting> lightings;  // trial seed s uses lightings[s % size]
  bool randomize = false;
  bool skipCalibration = false;
  std::vector<Venue> venues;        // trial seed s plays at venues[s % size]; none: balls from the seed
  double maxOffsetDeg = 3;
  double timeLimit = 600;           // s per phase (the rules' 10 min)
  double maxErrorM = 0.05;          // a report farther from the truth fails the trial
  double maxOffsetErrorDeg = 0.15;  // an estimated offset farther from the truth fails it too
  std::function<void(const nlohmann::json& row, int done, int total)> progress;
};

// What every row of this evaluation carries: rows of other settings are refused.
nlohmann::json challengeEvalSettings(const ChallengeEvalOptions& options);
// One trial: the challenge's JSON without its event log (the termination's event stays), with
// `seed`, `settings`, `lighting`, `failure` (null or why) and `wall_s`.
nlohmann::json runChallengeTrial(const ChallengeEvalOptions& options, std::uint64_t seed);
// `trials`, `terminations` (reason -> count), `categories` (name -> median, p95, max over the
// trials that have it), `task_error_m` (median, p95, max over every report), `offsets_error_deg`
// (p95, max of |error| over every parameter), `phase_s` (calibration, evaluation: median, p95,
// max), `within_0_05_m` (fraction of trials with every report within 0.05 m),
// `rounded_zero` (fraction with every report 0.0 m after the referee's rounding), `failures`
// [{seed, reason}].
nlohmann::json aggregateChallengeRows(std::vector<nlohmann::json> rows);
// The evaluation: `rows` are those already done (their seeds are not run again), `onRow` gets
// each new row as it ends.
nlohmann::json evalChallenge(const ChallengeEvalOptions& options, std::vector<nlohmann::json> rows = {},
                             const std::function<void(const nlohmann::json& row)>& onRow = {});

}  // namespace nao::sim
