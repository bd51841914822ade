#pragma once
// What both calibration solvers (Gauss-Newton, Ceres) report.
#include <string>
#include <vector>

#include "perception/calibration/CalibrationCost.h"

namespace nao::calibration {

enum class SolverKind { GaussNewton, Ceres };
inline const char* solverName(SolverKind k) { return k == SolverKind::GaussNewton ? "gauss-newton" : "ceres"; }
// "gauss-newton" or "ceres"; throws nao::Error("--solver", ...) otherwise.
SolverKind parseSolver(const std::string& name);

struct SolverResult {
  Params x{};                // the six offsets, rad
  std::vector<double> paint; // the paint's unknowns when the cost has them (CostOptions::paintTurns, paintDepth)
  bool converged = false;
  int iterations = 0;
  double initialCost = 0;    // 0.5 * sum of squared weighted residuals
  double finalCost = 0;
  double seconds = 0;        // wall time of the solve
  std::string message;       // why it stopped

  // Offsets and paint: what CalibrationCost::residuals takes.
  Eigen::VectorXd full() const {
    Eigen::VectorXd v(6 + static_cast<int>(paint.size()));
    for (int k = 0; k < 6; ++k) v[k] = x[k];
    for (std::size_t k = 0; k < paint.size(); ++k) v[6 + static_cast<int>(k)] = paint[k];
    return v;
  }
};

}  // namespace nao::calibration
