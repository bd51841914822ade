#include "controllers/modules/OwnBodyProvider.h"

#include "robot/ForwardKinematics.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

OwnBodyProvider::OwnBodyProvider(const ModuleContext& context) : params_(context.load<OwnBodyParams>(name())) {}

void OwnBodyProvider::update() {
  const CameraImage& image = in<CurrentImage>().image;
  JointArray joints{};
  Eigen::Isometry3d robotToTorso = Eigen::Isometry3d::Identity();
  if (!image.valid() || !in<FrameHistory>().at(image.timestamp, joints, robotToTorso)) {
    out<OwnBody>() = OwnBody{};
    return;
  }
  const CameraCalibration& calib = in<CameraCalibration>();
  Eigen::Isometry3d bodyOffset = Eigen::Isometry3d::Identity();
  bodyOffset.linear() = rotX(calib.bodyRoll) * rotY(calib.bodyPitch);
  out<OwnBody>() = ownBodyAt(joints, robotToTorso * bodyOffset, params_);
}

NAO_REGISTER_MODULE(OwnBodyProvider);

}  // namespace nao::modules
