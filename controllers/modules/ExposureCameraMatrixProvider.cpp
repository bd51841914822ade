#include "controllers/modules/ExposureCameraMatrixProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

void ExposureCameraMatrixProvider::update() {
  const CameraImage& image = in<CurrentImage>().image;
  auto& out = this->out<ImageCameraMatrix>();
  out.camera = image.camera;
  out.timestamp = image.timestamp;
  JointArray joints{};
  Eigen::Isometry3d robotToTorso = Eigen::Isometry3d::Identity();
  out.valid = image.valid() && in<FrameHistory>().at(image.timestamp, joints, robotToTorso);
  if (!out.valid) return;
  out.matrix = computeCameraMatrix(joints, robotToTorso, image.camera, in<CameraCalibration>(),
                                   CameraIntrinsics::fromFovY(image.width, image.height));
}

NAO_REGISTER_MODULE(ExposureCameraMatrixProvider);

}  // namespace nao::modules
