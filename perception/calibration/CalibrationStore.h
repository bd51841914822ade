#pragma once
// The calibration persisted per robot: one JSON file per head (the cameras and the neck sit in
// the head, so the head id is the key), <dir>/<headId>.json, by default config/calibration/.
// Loaded when the robot program starts (RobotProgramConfig::calibration) and applied by the
// camera model. A solution whose residuals are above the store's thresholds, or whose solver
// did not converge, is refused: a bad calibration on disk is worse than none.
//
//   {"head_id": "sim-r0-head",
//    "offsets_deg": {"body_roll": 0.12, "body_pitch": -1.3, "top_roll": ..., "top_pitch": ...,
//                    "bottom_roll": ..., "bottom_pitch": ...},
//    "rms_angle_deg": 0.02, "rms_depth_m": 0.0004, "samples": 10, "solver": "gauss-newton"}
#include <optional>
#include <string>

#include "perception/CameraCalibration.h"

namespace nao::calibration {

struct CalibrationRecord {
  CameraCalibration offsets;
  double rmsAngleDeg = 0, rmsDepthM = 0;
  int samples = 0;
  std::string solver;
  bool converged = true;
};

struct SaveOutcome {
  bool saved = false;
  std::string path;
  std::string reason;  // why refused
};

class CalibrationStore {
 public:
  // dir empty: config/calibration under the data root (robot/Paths.h).
  explicit CalibrationStore(std::string dir = {});
  const std::string& dir() const { return dir_; }
  // Throws nao::Error("head id", ...) for an id that is not a plain file name.
  std::string pathFor(const std::string& headId) const;

  // nullopt when the robot has no file yet; throws nao::Error(path, "key: problem") on a bad file.
  std::optional<CalibrationRecord> load(const std::string& headId) const;
  // The offsets to start the robot program with: the stored ones, or none.
  CameraCalibration offsetsFor(const std::string& headId) const;

  // Writes the record unless it is refused (not converged, residuals above the thresholds).
  // Throws nao::Error(path, ...) when the file cannot be written.
  SaveOutcome save(const std::string& headId, const CalibrationRecord& record) const;

  double maxRmsAngleDeg = 0.15;  // the same acceptance as the calibrator's defaults
  double maxRmsDepthM = 0.012;

  static CalibrationRecord parse(const std::string& jsonText, const std::string& sourceName);
  static std::string serialize(const std::string& headId, const CalibrationRecord& record);

 private:
  std::string dir_;
};

}  // namespace nao::calibration
