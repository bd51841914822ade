#include "perception/calibration/GaussNewtonSolver.h"

#include <chrono>
#include <cmath>

#include <Eigen/Cholesky>

#include "robot/Error.h"

namespace nao::calibration {

SolverKind parseSolver(const std::string& name) {
  if (name == "gauss-newton" || name == "gn") return SolverKind::GaussNewton;
  if (name == "ceres") return SolverKind::Ceres;
  throw Error("--solver", "must be gauss-newton or ceres, not '" + name + "'");
}

Eigen::MatrixXd numericalJacobian(const CalibrationCost& cost, const Eigen::VectorXd& x, double step) {
  const int m = cost.residualCount(), n = cost.parameterCount();
  Eigen::MatrixXd jac(m, n);
  Eigen::VectorXd plus(m), minus(m);
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd xp = x, xm = x;
    xp[k] += step;
    xm[k] -= step;
    cost.residuals(xp.data(), plus.data());
    cost.residuals(xm.data(), minus.data());
    jac.col(k) = (plus - minus) / (2 * step);
  }
  return jac;
}

Eigen::MatrixXd numericalJacobian(const CalibrationCost& cost, const Params& x, double step) {
  return numericalJacobian(cost, cost.parameters(x), step);
}

SolverResult solveGaussNewton(const CalibrationCost& cost, const Params& start, const GaussNewtonOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  SolverResult result;
  const int n = cost.parameterCount();
  Eigen::VectorXd x = cost.parameters(start);
  Eigen::VectorXd r = cost.residualsWithPaint(x);
  double f = 0.5 * r.squaredNorm();
  result.initialCost = f;
  int stable = 0;
  result.message = "iteration limit reached";
  for (int it = 0; it < options.maxIterations; ++it) {
    result.iterations = it + 1;
    const Eigen::MatrixXd jac = numericalJacobian(cost, x, options.jacobianStep);
    const Eigen::MatrixXd jtj = jac.transpose() * jac;
    const Eigen::VectorXd jtr = jac.transpose() * r;
    Eigen::LDLT<Eigen::MatrixXd> ldlt(jtj);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
      result.message = "singular normal equations: the samples do not determine all six offsets";
      break;
    }
    Eigen::VectorXd dx = -ldlt.solve(jtr);
    if (!dx.allFinite()) {
      result.message = "non-finite step";
      break;
    }
    // Halve the step while it raises the cost (only far from the solution).
    Eigen::VectorXd xn, rn;
    double fn = 0;
    int halvings = 0;
    for (;; ++halvings) {
      xn = x + dx;
      rn = cost.residualsWithPaint(xn);
      fn = 0.5 * rn.squaredNorm();
      if (fn <= f || halvings >= options.maxHalvings || dx.cwiseAbs().maxCoeff() < options.stepThreshold) break;
      dx /= 2;
    }
    if (fn > f && dx.cwiseAbs().maxCoeff() >= options.stepThreshold) {
      result.message = "no step lowers the cost";
      break;
    }
    if (fn <= f) {
      x = xn;
      r = rn;
      f = fn;
    }
    stable = dx.cwiseAbs().maxCoeff() < options.stepThreshold ? stable + 1 : 0;
    if (stable >= options.stableSteps) {
      result.converged = true;
      result.message = "parameter change below threshold";
      break;
    }
  }
  for (int k = 0; k < 6; ++k) result.x[k] = x[k];
  result.paint.assign(x.data() + 6, x.data() + n);
  result.finalCost = f;
  if (!x.allFinite()) result.converged = false;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace nao::calibration
