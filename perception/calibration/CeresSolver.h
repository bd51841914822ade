#pragma once
// The same residuals as Gauss-Newton (CalibrationCost) minimised by Ceres (Levenberg-Marquardt,
// dense QR, central-difference Jacobian): a second, independent solver to check the first.
#include "perception/calibration/Solver.h"

namespace nao::calibration {

struct CeresOptions {
  int maxIterations = 100;
  double functionTolerance = 1e-15;
  double parameterTolerance = 1e-12;
  double gradientTolerance = 1e-15;
};

// False in an executable built without Ceres (CeresSolverAbsent.cpp: nao-soccer-robot).
bool ceresAvailable();
SolverResult solveCeres(const CalibrationCost& cost, const Params& start = {}, const CeresOptions& options = {});

}  // namespace nao::calibration
