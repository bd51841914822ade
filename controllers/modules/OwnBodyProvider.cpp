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
  out<OwnBody>() = ownBodyAt(joints, robotToTorso * bodyOffset(in<CameraCalibration>()), params_);
}

NAO_REGISTER_MODULE(OwnBodyProvider);

}  // namespace nao::modules
