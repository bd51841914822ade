#pragma once
// Gauss-Newton on the calibration cost, as B-Human does it: the cost is awkward to
// differentiate by hand (kinematic chain, projection to the ground, bisectors, intersections),
// so the Jacobian is approximated by central differences. A step that would raise the cost
// is halved until it does not (a plain GN step can overshoot far from the solution). The
// solve is done once the largest parameter change stays below a threshold for several
// consecutive steps.
#include "perception/calibration/Solver.h"

namespace nao::calibration {

struct GaussNewtonOptions {
  int maxIterations = 100;
  double jacobianStep = 1e-6;      // rad, central differences
  double stepThreshold = 1e-9;     // rad: a step whose largest component stays below this ...
  int stableSteps = 3;             // ... this many times in a row ends the solve
  int maxHalvings = 30;
};

SolverResult solveGaussNewton(const CalibrationCost& cost, const Params& start = {},
                              const GaussNewtonOptions& options = {});

// The numerical Jacobian (central differences) of the weighted residuals at x (all of the
// cost's parameterCount() parameters; with a Params the paint's unknowns are zero).
Eigen::MatrixXd numericalJacobian(const CalibrationCost& cost, const Eigen::VectorXd& x, double step = 1e-6);
Eigen::MatrixXd numericalJacobian(const CalibrationCost& cost, const Params& x, double step = 1e-6);

}  // namespace nao::calibration
