#include "scenarios/ProgramMetering.h"

#include "robot/ForwardKinematics.h"
#include "robot/Parameters.h"

namespace nao {

ProgramMetering::ProgramMetering(const std::string& configDir) {
  if (configDir.empty()) return;
  weighting_ = loadParams<ExposureWeightingParams>("AutoExposureWeighting", configDir);
  body_ = loadParams<OwnBodyParams>("OwnBodyProvider", configDir);
}

ExposureWeights ProgramMetering::operator()(const CameraMatrix& cm, const JointArray& joints,
                                            const Eigen::Isometry3d& robotToTorso,
                                            const CameraCalibration& calibration) const {
  Eigen::Isometry3d bodyOffset = Eigen::Isometry3d::Identity();
  bodyOffset.linear() = rotX(calibration.bodyRoll) * rotY(calibration.bodyPitch);
  return exposureWeights(cm, ownBodyAt(joints, robotToTorso * bodyOffset, body_), weighting_);
}

}  // namespace nao
