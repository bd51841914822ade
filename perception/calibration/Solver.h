#pragma once
// What both calibration solvers (Gauss-Newton, Ceres) report.
#include <string>

#include "perception/calibration/CalibrationCost.h"

namespace nao::calibration {

enum class SolverKind { GaussNewton, Ceres };
inline const char* solverName(SolverKind k) { return k == SolverKind::GaussNewton ? "gauss-newton" : "ceres"; }
// "gauss-newton" or "ceres"; throws nao::Error("--solver", ...) otherwise.
SolverKind parseSolver(const std::string& name);

struct SolverResult {
  Params x{};                // rad
  bool converged = false;
  int iterations = 0;
  double initialCost = 0;    // 0.5 * sum of squared weighted residuals
  double finalCost = 0;
  double seconds = 0;        // wall time of the solve
  std::string message;       // why it stopped
};

}  // namespace nao::calibration
