#pragma once
// `eval localization`: the unchanged robot program (SelfLocalization, BallLocator,
// BehaviorControl with the operator's goTo command) in the simulator with both cameras, scored
// against the simulator's truth. One trial per seed: the robot enters at a side line of its
// own half (the game situation the localization starts from), a ball lies at random, and the
// scenario (the operator) sends it to 3-4 random field poses in turn. Some trials end with a
// kidnap (the referee lifts the robot and sets it down 1-3 m and 45-180 deg away; the filter is
// not told) or a rolling ball (kicked 1-4 m while the robot stands and watches). Every trial's
// figures are one row (JSON); the aggregate is computed from the rows sorted by seed, so a run
// resumed from a rows file (--rows) gives the same aggregate as one uninterrupted run.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "sim/Lighting.h"

namespace nao {
class DebugChannels;
}

namespace nao::sim {

enum class LocalizationTrialKind { Walk, Kidnap, Rolling };

struct LocalizationEvalOptions {
  FieldDimensions field;
  int trials = 8;
  std::uint64_t seed = 1;  // trial i has seed `seed + i`; everything in a trial follows from its seed
  std::vector<std::uint64_t> seeds;  // not empty: exactly these trials (trials and seed aside)
  // The presets; trial seed s uses lightings[s % size] (one entry: every trial the same).
  std::vector<Lighting> lightings{Lighting{}};
  bool randomize = false;  // foreign robots (as eval walk --randomize) and camera offsets it was calibrated for
  double residualDeg = 0.15;  // with randomize: the calibration's residual error per offset, uniform +-DEG
  double walkSeconds = 20;    // the scripted walk of every trial (simulated s)
  int kidnapEvery = 4;        // trial seeds with s % kidnapEvery == kidnapEvery - 1 end with a kidnap; 0: none
  int rollEvery = 4;          // trial seeds with s % rollEvery == 1 end with a rolling ball (unless kidnapped); 0: none
  bool oracle = false;        // the fast percept mode (OracleVision, nothing rendered) instead of the vision
  std::function<void(const nlohmann::json& row, int done, int total)> progress;  // after each trial
  DebugChannels* debug = nullptr;  // the robot program's debug channels (not owned); null: none
};

// Settings a row was made with: rows of other settings are refused when resuming.
nlohmann::json localizationEvalSettings(const LocalizationEvalOptions& options);

// One trial: its row (seed, lighting, kind, raw samples rounded as stored, wall_s).
nlohmann::json runLocalizationTrial(const LocalizationEvalOptions& options, std::uint64_t trialSeed);

// The aggregate of rows (any order; sorted by seed here): the `eval localization` JSON with
// `by_lighting`.
nlohmann::json aggregateLocalizationRows(std::vector<nlohmann::json> rows);

// The whole evaluation. `rows` holds rows already done (from --rows; seeds of this run are not
// run again); `onRow` is called with each new row as it ends (to append it to the file).
nlohmann::json evalLocalization(const LocalizationEvalOptions& options, std::vector<nlohmann::json> rows = {},
                                const std::function<void(const nlohmann::json& row)>& onRow = {});

}  // namespace nao::sim
