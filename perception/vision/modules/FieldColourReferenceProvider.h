#pragma once
// This image's field colour and white point in the units of the white and field tests
// (vision::FieldReference::from).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/vision/VisionTypes.h"
#include "representations/perception/FieldColourReference.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class FieldColourReferenceProvider : public Module<FieldColourReferenceProvider, Requires<ScanLineRegions>,
                                                   Provides<FieldColourReference>, Cadence::Cognition> {
 public:
  explicit FieldColourReferenceProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
