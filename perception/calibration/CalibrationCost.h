#pragma once
// The calibration's least-squares cost (B-Human 2021, section 3). With candidate offsets the
// camera matrix of each sample is rebuilt from its joint angles and IMU angles, the paint
// edges of its three lines are projected to the ground, and each line's centre is the
// bisector of its two projected edges. Per sample, three residuals that need no knowledge of
// where the robot stands, only of relative angles and distances on the field:
//   - the two right angles between the short line and each long line,
//   - the goal box's depth: the distance between the short line's two junctions with the long
//     lines (= field.goalBoxAreaLength between line centres).
// and, on by default, a fourth: the parallelism of the two long lines. For exact data it is
// implied by the two right angles, but it weights the two long, well-measured lines' common
// vanishing point on its own, which pins the pitch without the depth.
// Residuals are weighted by their expected errors so that angles and distances add up in one
// sum: angle residuals are sin(deviation) / angleSigma, the depth residual is
// (depth - goalBoxAreaLength) / depthSigma. The depth scales with the camera's height above the
// ground, which the leg kinematics know to a few millimetres only (a real carpet gives way), so
// depthSigma is that uncertainty (2 mm), not the image's (a fraction of a millimetre): weighted
// by the image alone, a 1 mm height error would tilt the pitch estimates by 0.05 deg.
// Measured in the simulator (30 trials): parallelism plus the 2 mm depth weight cut the median
// pitch errors from 0.013 to 0.002 deg and the reprojection error from 0.12 to 0.02 px.
#include <array>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/CalibrationSample.h"

namespace nao::calibration {

using Params = std::array<double, 6>;  // CameraCalibration::toArray() order, rad

struct CostOptions {
  double goalBoxDepth = 0.6;             // m, field.goalBoxAreaLength
  double angleSigma = 0.02 * std::numbers::pi / 180;  // rad per right-angle residual
  double depthSigma = 0.002;             // m per depth residual
  bool parallelism = true;               // add the long lines' parallelism (weight angleSigma)

  static CostOptions forField(const FieldDimensions& field);
};

// A sample's unweighted residuals, for people: angle deviations in deg, depth error in m.
struct SampleResiduals {
  double angle1Deg = 0, angle2Deg = 0, depthErrorM = 0, parallelDeg = 0;
  bool projected = true;  // false when a line did not reach the ground (above the horizon)
};

class CalibrationCost {
 public:
  // Throws nao::Error("calibration", ...) when there are no samples or an option is not positive.
  CalibrationCost(std::vector<CalibrationSample> samples, const CostOptions& options);

  int residualsPerSample() const { return options_.parallelism ? 4 : 3; }
  int residualCount() const { return residualsPerSample() * static_cast<int>(samples_.size()); }
  const std::vector<CalibrationSample>& samples() const { return samples_; }
  const CostOptions& options() const { return options_; }

  // Weighted residuals for parameters x (residualCount() values into r). A line that does
  // not reach the ground with x gets a large constant residual (kUnprojectable).
  void residuals(const double* x, double* r) const;
  Eigen::VectorXd residuals(const Params& x) const;
  // 0.5 * sum of squared weighted residuals.
  double cost(const Params& x) const;
  SampleResiduals sampleResiduals(const Params& x, int sample) const;
  // The ground lines (robot frame) of a sample's three line centres with x: a point and a
  // unit direction each; nullopt-like (false) when one does not project.
  bool groundLines(const Params& x, int sample, std::array<Eigen::ParametrizedLine<double, 2>, 3>& out) const;

  // Per-sample factors on the residuals (robust reweighting); all 1 unless set.
  void setSampleWeights(std::vector<double> weights);

  static constexpr double kUnprojectable = 1e3;

 private:
  std::vector<double> weights_;
  std::vector<CalibrationSample> samples_;
  std::vector<Eigen::Isometry3d> robotToTorso_;  // per sample: independent of the offsets
  CostOptions options_;
};

}  // namespace nao::calibration
