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
  // The image's size is enough: the fast percept mode's images have no pixels.
  out.valid = image.width > 0 && image.height > 0 && in<FrameHistory>().at(image.timestamp, joints, robotToTorso);
  if (!out.valid) return;
  out.matrix = computeCameraMatrix(joints, robotToTorso, image.camera, in<CameraCalibration>(),
                                   CameraIntrinsics::fromFovY(image.width, image.height));
}

NAO_REGISTER_MODULE(ExposureCameraMatrixProvider);

}  // namespace nao::modules
