#include "perception/calibration/CeresSolver.h"

#include <chrono>
#include <vector>

#include <ceres/ceres.h>

namespace nao::calibration {
namespace {

struct Residuals {
  const CalibrationCost* cost;
  bool operator()(double const* const* parameters, double* residuals) const {
    cost->residuals(parameters[0], residuals);
    return true;
  }
};

}  // namespace

bool ceresAvailable() { return true; }

SolverResult solveCeres(const CalibrationCost& cost, const Params& start, const CeresOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  SolverResult result;
  const int n = cost.parameterCount();
  std::vector<double> x(n, 0.0);
  for (int k = 0; k < 6; ++k) x[k] = start[k];
  auto* fn = new ceres::DynamicNumericDiffCostFunction<Residuals, ceres::CENTRAL>(new Residuals{&cost});
  fn->AddParameterBlock(n);
  fn->SetNumResiduals(cost.residualCount());
  ceres::Problem problem;  // owns fn
  problem.AddResidualBlock(fn, nullptr, x.data());

  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = options.maxIterations;
  o.function_tolerance = options.functionTolerance;
  o.parameter_tolerance = options.parameterTolerance;
  o.gradient_tolerance = options.gradientTolerance;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  o.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);

  for (int k = 0; k < 6; ++k) result.x[k] = x[k];
  result.paint.assign(x.begin() + 6, x.end());
  result.iterations = static_cast<int>(summary.iterations.size());
  result.initialCost = summary.initial_cost;
  result.finalCost = summary.final_cost;
  result.converged = summary.termination_type == ceres::CONVERGENCE && summary.IsSolutionUsable();
  result.message = summary.message;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace nao::calibration
