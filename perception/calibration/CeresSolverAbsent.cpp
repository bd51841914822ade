// solveCeres for executables built without Ceres (nao-soccer-robot, perception/CMakeLists.txt):
// the robot calibrates with Gauss-Newton, and asking for the second solver there is bad input.
#include "robot/Error.h"
#include "perception/calibration/CeresSolver.h"

namespace nao::calibration {

bool ceresAvailable() { return false; }

SolverResult solveCeres(const CalibrationCost&, const Params&, const CeresOptions&) {
  throw Error("--solver", "ceres is not built into this executable (nao-soccer-robot); use gauss-newton");
}

}  // namespace nao::calibration
