#include "perception/calibration/Calibrator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "robot/Error.h"

namespace nao::calibration {
namespace {

// Enough samples per camera, at two or more pan angles (one angle cannot tell body offsets
// from camera offsets).
std::string observabilityProblem(const std::vector<CalibrationSample>& samples, const std::vector<int>& used,
                                 int minPerCamera) {
  for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
    int n = 0;
    std::set<long> yaws;
    for (int i : used)
      if (samples[i].camera == cam) {
        ++n;
        yaws.insert(std::lround(samples[i].headYaw() * 180 / M_PI));
      }
    if (n < minPerCamera)
      return std::string(cameraName(cam)) + " camera: " + std::to_string(n) + " samples, at least " +
             std::to_string(minPerCamera) + " needed";
    if (yaws.size() < 2) return std::string(cameraName(cam)) + " camera: all samples at one head pan angle";
  }
  return {};
}

std::vector<CalibrationSample> subset(const std::vector<CalibrationSample>& samples, const std::vector<int>& used) {
  std::vector<CalibrationSample> out;
  for (int i : used) out.push_back(samples[i]);
  return out;
}

}  // namespace

SolverResult solveWith(SolverKind kind, const CalibrationCost& cost, const CalibratorOptions& options) {
  return kind == SolverKind::GaussNewton ? solveGaussNewton(cost, {}, options.gaussNewton)
                                         : solveCeres(cost, {}, options.ceres);
}

CalibrationSolution solveCalibration(const std::vector<CalibrationSample>& samples, const CalibratorOptions& options) {
  CalibrationSolution sol;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) sol.used.push_back(i);
  if (const std::string problem = observabilityProblem(samples, sol.used, options.minSamplesPerCamera); !problem.empty())
    throw Error("calibration", problem);

  const int k = options.cost.parallelism ? 4 : 3;
  const double floor = options.outlierFloor * std::sqrt(k);
  for (;;) {
    const CalibrationCost cost(subset(samples, sol.used), options.cost);
    sol.solver = solveWith(options.solver, cost, options);
    sol.solveSeconds += sol.solver.seconds;
    // Per sample: the norm of its weighted residuals. All small: done.
    const Eigen::VectorXd r = cost.residualsWithPaint(sol.solver.full());
    double worstIn = 0;
    for (std::size_t i = 0; i < sol.used.size(); ++i) worstIn = std::max(worstIn, r.segment(k * i, k).norm());
    if (worstIn <= floor) break;
    // A bad sample pulls the least-squares solution towards itself and hides among the rest.
    // Iteratively reweighted least squares (Cauchy weights) finds the solution the majority
    // agrees on; the sample that fits it worst is the candidate.
    CalibrationCost robust(subset(samples, sol.used), options.cost);
    std::vector<double> norms(sol.used.size());
    for (std::size_t i = 0; i < sol.used.size(); ++i) norms[i] = r.segment(k * i, k).norm();
    for (int round = 0; round < 8; ++round) {
      std::vector<double> sorted = norms;
      std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
      const double scale = std::max(floor, 1.5 * sorted[sorted.size() / 2]);
      std::vector<double> weights;
      for (double n : norms) weights.push_back(1 / std::sqrt(1 + (n / scale) * (n / scale)));
      robust.setSampleWeights(weights);
      const SolverResult s = solveWith(options.solver, robust, options);
      sol.solveSeconds += s.seconds;
      robust.setSampleWeights({});
      const Eigen::VectorXd rr = robust.residualsWithPaint(s.full());
      for (std::size_t i = 0; i < sol.used.size(); ++i) norms[i] = rr.segment(k * i, k).norm();
    }
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const auto worst = std::max_element(norms.begin(), norms.end()) - norms.begin();
    if (!(norms[worst] > options.outlierFactor * median && norms[worst] > floor)) break;
    std::vector<int> fewer = sol.used;
    fewer.erase(fewer.begin() + worst);
    if (!observabilityProblem(samples, fewer, options.minSamplesPerCamera).empty()) break;
    char why[96];
    std::snprintf(why, sizeof why, "fits %.1f times worse than the median sample (robust solve)",
                  norms[worst] / std::max(median, 1e-12));
    sol.dropped.emplace_back(sol.used[worst], why);
    sol.used = fewer;
  }

  sol.offsets = CameraCalibration::fromArray(sol.solver.x);
  const CalibrationCost cost(subset(samples, sol.used), options.cost);
  double a2 = 0, d2 = 0;
  for (int i = 0; i < static_cast<int>(sol.used.size()); ++i) {
    const SampleResiduals s = cost.sampleResidualsWithPaint(sol.solver.full(), i);
    sol.residuals.push_back(s);
    a2 += s.angle1Deg * s.angle1Deg + s.angle2Deg * s.angle2Deg;
    d2 += s.depthErrorM * s.depthErrorM;
  }
  sol.rmsAngleDeg = std::sqrt(a2 / (2 * sol.used.size()));
  sol.rmsDepthM = std::sqrt(d2 / sol.used.size());
  char buf[160];
  if (!sol.solver.converged) {
    sol.reason = "the solver did not converge: " + sol.solver.message;
  } else if (sol.rmsAngleDeg > options.maxRmsAngleDeg) {
    std::snprintf(buf, sizeof buf, "right-angle residuals %.3f deg RMS exceed %.3f deg", sol.rmsAngleDeg,
                  options.maxRmsAngleDeg);
    sol.reason = buf;
  } else if (sol.rmsDepthM > options.maxRmsDepthM) {
    std::snprintf(buf, sizeof buf, "goal-box depth residuals %.4f m RMS exceed %.4f m", sol.rmsDepthM,
                  options.maxRmsDepthM);
    sol.reason = buf;
  } else {
    sol.accepted = true;
  }
  return sol;
}

}  // namespace nao::calibration
