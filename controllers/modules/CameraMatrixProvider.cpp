#include "controllers/modules/CameraMatrixProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

void CameraMatrixProvider::update() {
  // The intrinsics follow the resolution the camera actually delivers.
  for (int c = 0; c < kNumCameras; ++c)
    if (const auto& img = in<CameraImages>().latest[c];
        img && (img->width != intrinsics_[c].width || img->height != intrinsics_[c].height))
      intrinsics_[c] = CameraIntrinsics::fromFovY(img->width, img->height);
  const SensorFrame& frame = in<SensorFrame>();
  auto& matrices = out<CameraMatrices>();
  for (CameraId cam : {CameraId::Top, CameraId::Bottom})
    matrices.matrix[static_cast<int>(cam)] =
        computeCameraMatrix(frame.joints.position, in<TorsoState>().robotToTorso, cam, in<CameraCalibration>(),
                            intrinsics_[static_cast<int>(cam)]);
}

NAO_REGISTER_MODULE(CameraMatrixProvider);

}  // namespace nao::modules
