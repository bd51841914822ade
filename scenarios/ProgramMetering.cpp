#include "scenarios/ProgramMetering.h"

#include "robot/ForwardKinematics.h"
#include "robot/Parameters.h"

namespace nao {

ProgramMetering::ProgramMetering(const std::string& configDir) {
  if (configDir.empty()) return;
  weighting_ = loadParams<ExposureWeightingParams>("AutoExposureWeighting", configDir);
  body_ = loadParams<OwnBodyParams>("OwnBodyProvider", configDir);
}

ExposureWeights ProgramMetering::operator()(const CameraMatrix& cm, const SensorFrame& sensors,
                                            const CameraCalibration& calibration) const {
  const Eigen::Isometry3d torso = robotToTorso(sensors) * bodyOffset(calibration);
  return exposureWeights(cm, ownBodyAt(sensors.joints.position, torso, body_), weighting_);
}

}  // namespace nao
