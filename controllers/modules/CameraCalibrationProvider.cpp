#include "controllers/modules/CameraCalibrationProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

CameraCalibrationProvider::CameraCalibrationProvider(const ModuleContext& context) {
  if (auto it = context.params.find(name()); it != context.params.end())
    if (const auto* c = std::any_cast<CameraCalibration>(&it->second)) current_ = *c;
}

void CameraCalibrationProvider::update() {
  const CalibrationStatus& status = in<CalibrationStatus>();
  // A new solution applied; a status cleared (a new challenge mode) keeps the one in use.
  if (status.appliedId != appliedId_) {
    appliedId_ = status.appliedId;
    if (appliedId_ != 0) current_ = status.applied;
  }
  out<CameraCalibration>() = current_;
}

NAO_REGISTER_MODULE(CameraCalibrationProvider);

}  // namespace nao::modules
