#include "controllers/modules/Calibrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "controllers/modules/ModuleField.h"
#include "perception/calibration/CalibrationCost.h"
#include "robot/Error.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {
NAO_DEBUG_CHANNEL(kCalibration, "calibration",
                  "the calibrator: each view's sample or why none, each solve, apply and verification");
constexpr double kDeg = M_PI / 180;
// Why an image was not taken because of motion (the next still image may do); one place for the words.
constexpr const char* kNotStillYet = "not still long enough yet";
constexpr const char* kHeadMoving = "head moving";
constexpr const char* kTorsoMoving = "torso moving";
bool isStillnessReason(const std::string& r) { return r == kNotStillYet || r == kHeadMoving || r == kTorsoMoving; }

// The largest change of the head joints and of the torso's roll and pitch over [from, to].
struct Motion {
  double joint = 0, imu = 0;
  bool covered = false;  // the history reaches back to `from`
};
Motion motionOver(const FrameHistory& history, double from, double to) {
  Motion m;
  if (history.entries.empty()) return m;
  m.covered = history.entries.front().time <= from + 1e-9;
  double lo[4] = {1e9, 1e9, 1e9, 1e9}, hi[4] = {-1e9, -1e9, -1e9, -1e9};
  for (const auto& e : history.entries) {
    if (e.time < from - 1e-9 || e.time > to + 0.013) continue;  // and the cycle after the exposure
    const double v[4] = {e.joints[HeadYaw], e.joints[HeadPitch], e.imuAngle.x(), e.imuAngle.y()};
    for (int k = 0; k < 4; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  }
  m.joint = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  m.imu = std::max(hi[2] - lo[2], hi[3] - lo[3]);
  return m;
}
}  // namespace

Calibrator::Calibrator(const ModuleContext& context) : params_(context.load<Params>(name())) {
  const FieldDimensions field = fieldFor(context);
  extraction_.goalBoxDepth = field.goalBoxAreaLength;
  extraction_.lineWidth = field.lineWidth;
  solver_.cost = calibration::CostOptions::forField(field);
  solver_.cost.depthSigma = params_.depthSigmaM;
  solver_.cost.angleSigma = params_.angleSigmaDeg * std::numbers::pi / 180;
  solver_.cost.paintTurns = params_.paintTurns;
  solver_.cost.paintDepth = params_.paintDepth;
  solver_.cost.turnPriorSigma = params_.turnPriorDeg * std::numbers::pi / 180;
  solver_.cost.depthPriorSigma = params_.depthPriorM;
  solver_.minSamplesPerCamera = params_.minSamplesPerCamera;
  solver_.maxRmsAngleDeg = params_.maxRmsAngleDeg;
  solver_.maxRmsDepthM = params_.maxRmsDepthM;
  if (params_.solver != "gauss-newton" && params_.solver != "ceres")
    throw Error("Calibrator.solver", "must be gauss-newton or ceres, not '" + params_.solver + "'");
  solver_.solver = calibration::parseSolver(params_.solver);
  if ((solver_.solver == calibration::SolverKind::Ceres || params_.compareSolvers) && !calibration::ceresAvailable())
    throw Error(params_.compareSolvers ? "Calibrator.compareSolvers" : "Calibrator.solver",
                "needs Ceres, which this executable is built without (nao-soccer-robot): use gauss-newton alone");
  extraction_.source = calibration::lineSourceFromName(params_.lines, "Calibrator.lines");
}

void Calibrator::reset() {
  samples_.clear();
  verifiedViewId_ = -1;
  CalibrationStatus& status = out<CalibrationStatus>();
  const int appliedId = status.appliedId;  // stays: CameraCalibrationProvider keeps what it has
  const CameraCalibration applied = status.applied;
  const int solutionId = status.solutionId;
  status = CalibrationStatus{};
  status.appliedId = appliedId;
  status.applied = applied;
  status.solutionId = solutionId;  // ids keep counting: a stale request must not match a new solve
}

calibration::ExtractionResult Calibrator::extract(const CameraImage& image, const CameraCalibration& current) const {
  calibration::ExtractionResult r;
  const FrameHistory& history = in<FrameHistory>();
  const Motion m = motionOver(history, image.timestamp - params_.stillSeconds, image.timestamp);
  if (!m.covered) {
    r.reason = kNotStillYet;
  } else if (m.joint > params_.stillJointRad) {
    r.reason = kHeadMoving;
  } else if (m.imu > params_.stillImuRad) {
    r.reason = kTorsoMoving;
  }
  if (!r.reason.empty()) return r;
  JointArray joints{};
  Eigen::Isometry3d robotToTorso;
  Eigen::Vector2d imu;
  history.at(image.timestamp, joints, robotToTorso);
  history.imuAngleAt(image.timestamp, imu);
  return calibration::extractSample(image, joints, imu, CameraIntrinsics::fromFovY(image.width, image.height), current,
                                    extraction_);
}

void Calibrator::update() {
  CalibrationStatus& status = out<CalibrationStatus>();
  const ChallengeMode& mode = in<ChallengeMode>();
  const CalibrationRequest& request = in<CalibrationRequest>();
  if (mode.modeId != modeId_) {
    modeId_ = mode.modeId;
    reset();
  }
  const CameraImage& image = in<CurrentImage>().image;
  switch (request.action) {
    case CalibrationRequest::Action::Idle: break;
    case CalibrationRequest::Action::Reset: reset(); break;
    case CalibrationRequest::Action::Collect: {
      if (request.viewId == status.last.viewId || image.camera != request.camera || !image.valid()) break;
      // The sample is measured against the uncalibrated zero: the solve estimates the offsets
      // from there.
      const auto t0 = std::chrono::steady_clock::now();
      const calibration::ExtractionResult r = extract(image, CameraCalibration{});
      if (!r.sample && isStillnessReason(r.reason)) {
        status.last.reason = r.reason;  // not this image; the next one may do
        break;
      }
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      status.last = {request.viewId, r.sample.has_value(), r.sample ? "" : r.reason, image.timestamp, ms, r.source};
      if (r.sample) {
        samples_.push_back(*r.sample);
        ++status.samples[static_cast<int>(image.camera)];
      }
      debug(kCalibration, [&] {
        return nlohmann::json{{"view", request.viewId}, {"camera", cameraName(image.camera)},
                              {"head_yaw_deg", r.sample ? r.sample->headYaw() / kDeg : 0.0},
                              {"accepted", r.sample.has_value()}, {"reason", status.last.reason}};
      });
      break;
    }
    case CalibrationRequest::Action::Solve: {
      if (request.solutionId == status.solutionId) break;
      status.solutionId = request.solutionId;
      status.converged = status.accepted = false;
      status.reason.clear();
      try {
        status.otherSolver.reset();
        const calibration::CalibrationSolution s = calibration::solveCalibration(samples_, solver_);
        status.solution = s;
        if (params_.compareSolvers && !s.used.empty()) {
          std::vector<calibration::CalibrationSample> used;
          for (int i : s.used) used.push_back(samples_[static_cast<std::size_t>(i)]);
          const calibration::SolverKind other = solver_.solver == calibration::SolverKind::GaussNewton
                                                    ? calibration::SolverKind::Ceres
                                                    : calibration::SolverKind::GaussNewton;
          status.otherSolver = calibration::solveWith(other, calibration::CalibrationCost(used, solver_.cost), solver_);
        }
        status.offsets = s.offsets;
        status.converged = s.solver.converged;
        status.accepted = s.accepted;
        status.reason = s.reason;
        status.rmsAngleDeg = s.rmsAngleDeg;
        status.rmsDepthM = s.rmsDepthM;
        for (double v : s.offsets.toArray())
          if (std::abs(v) > params_.maxOffsetDeg * kDeg && status.accepted) {
            status.accepted = false;
            status.reason = "implausible: an offset beyond " + std::to_string(params_.maxOffsetDeg).substr(0, 4) + " deg";
          }
        status.solution.accepted = status.accepted;
        status.solution.reason = status.reason;
      } catch (const Error& e) {
        status.reason = e.what();
        status.solution = {};
        status.solution.reason = status.solution.solver.message = e.what();
      }
      debug(kCalibration, [&] {
        const auto a = status.offsets.toArray();
        return nlohmann::json{{"solve", status.solutionId},
                              {"samples", {status.samples[0], status.samples[1]}},
                              {"offsets_deg", {a[0] / kDeg, a[1] / kDeg, a[2] / kDeg, a[3] / kDeg, a[4] / kDeg, a[5] / kDeg}},
                              {"accepted", status.accepted},
                              {"reason", status.reason},
                              {"rms_angle_deg", status.rmsAngleDeg},
                              {"paint", status.solution.solver.paint}};
      });
      break;
    }
    case CalibrationRequest::Action::Apply:
      if (request.solutionId == status.solutionId && status.accepted &&
          !(status.appliedId != 0 && status.applied.toArray() == status.offsets.toArray())) {
        status.applied = status.offsets;
        ++status.appliedId;
        status.verifyAngleDeg = -1;
      }
      break;
    case CalibrationRequest::Action::Verify: {
      if (status.appliedId == 0 || request.viewId == verifiedViewId_ || image.camera != request.camera ||
          !image.valid())
        break;
      const calibration::ExtractionResult r = extract(image, status.applied);
      if (!r.sample) {
        status.last.reason = r.reason;
        break;
      }
      verifiedViewId_ = request.viewId;
      // The new view's residuals at the applied offsets: a calibration that holds leaves the
      // goal box's corners right angles.
      const calibration::CalibrationCost cost({*r.sample}, solver_.cost);
      // With the paint as unknowns, against the paint the solve found.
      const calibration::SampleResiduals res =
          cost.sampleResidualsWithPaint(cost.parameters(status.applied.toArray(), status.solution.solver.paint), 0);
      status.verifyAngleDeg = res.projected ? std::max({std::abs(res.angle1Deg), std::abs(res.angle2Deg),
                                                        std::abs(res.parallelDeg)})
                                            : 90.0;
      debug(kCalibration, [&] { return nlohmann::json{{"verify", request.viewId}, {"angle_deg", status.verifyAngleDeg}}; });
      break;
    }
  }
}

NAO_REGISTER_MODULE(Calibrator);

}  // namespace nao::modules
