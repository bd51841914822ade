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
  // The paint as unknowns beside the six offsets (docs/calibration/README.md, "Telling the paint
  // from the cameras"). Off, a long line painted a little turned about its junction moves the
  // pitches instead; on, views from two distances tell the two apart. All samples must show
  // the same box corner: the turns belong to the long lines as the image orders them (the one
  // meeting the short line further left, the other), which is the same physical line in every
  // view of one corner. Each unknown has a prior residual (value / sigma): the paint's accuracy.
  bool paintTurns = false;               // two unknowns: the left and the right long line's turn (rad, ccw)
  bool paintDepth = false;               // one unknown: the painted box's depth minus goalBoxDepth (m)
  double turnPriorSigma = 0.5 * std::numbers::pi / 180;  // rad
  double depthPriorSigma = 0.01;         // m

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
  // The six offsets, then the paint's unknowns (left turn, right turn, depth; those switched on).
  int parameterCount() const { return 6 + paintCount(); }
  int paintCount() const { return (options_.paintTurns ? 2 : 0) + (options_.paintDepth ? 1 : 0); }
  // Per sample, then one prior per paint unknown.
  int residualCount() const { return residualsPerSample() * static_cast<int>(samples_.size()) + paintCount(); }
  const std::vector<CalibrationSample>& samples() const { return samples_; }
  const CostOptions& options() const { return options_; }

  // Weighted residuals for parameters x (parameterCount() values; residualCount() values into
  // r). A line that does not reach the ground with x gets a large constant residual
  // (kUnprojectable).
  void residuals(const double* x, double* r) const;
  // All parameterCount() parameters: the offsets, then the paint (zeros, the rules' paint,
  // unless `paint` holds paintCount() values).
  Eigen::VectorXd parameters(const Params& offsets, const std::vector<double>& paint = {}) const;
  // With the paint's unknowns (if any) at zero: the paint as the rules draw it.
  Eigen::VectorXd residuals(const Params& x) const;
  Eigen::VectorXd residualsWithPaint(const Eigen::VectorXd& x) const;  // all parameterCount() values
  // 0.5 * sum of squared weighted residuals.
  double cost(const Params& x) const;
  // Against the paint x's unknowns describe (the rules' paint with a Params).
  SampleResiduals sampleResiduals(const Params& x, int sample) const;
  SampleResiduals sampleResidualsWithPaint(const Eigen::VectorXd& x, int sample) const;
  // The ground lines (robot frame) of a sample's three line centres with x: a point and a
  // unit direction each; nullopt-like (false) when one does not project.
  bool groundLines(const Params& x, int sample, std::array<Eigen::ParametrizedLine<double, 2>, 3>& out) const;

  // Per-sample factors on the residuals (robust reweighting); all 1 unless set.
  void setSampleWeights(std::vector<double> weights);

  static constexpr double kUnprojectable = 1e3;

 private:
  // The paint's unknowns in x (0 when not estimated): a long line's turn, the depth's error.
  double turnOf(const double* x, int sample, int role) const;
  double depthErrorOf(const double* x) const { return options_.paintDepth ? x[6 + (options_.paintTurns ? 2 : 0)] : 0; }
  void sampleResiduals(const double* x, int sample, SampleResiduals& out) const;

  std::vector<double> weights_;
  std::vector<CalibrationSample> samples_;
  std::vector<char> longLine1IsLeft_;  // per sample: long line 1 meets the short line left of long line 2
  std::vector<Eigen::Isometry3d> robotToTorso_;  // per sample: independent of the offsets
  CostOptions options_;
};

}  // namespace nao::calibration
