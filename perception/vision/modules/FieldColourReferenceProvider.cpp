#include "perception/vision/modules/FieldColourReferenceProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

FieldColourReferenceProvider::FieldColourReferenceProvider(const ModuleContext&) {}

void FieldColourReferenceProvider::update() {
  static_cast<vision::FieldReference&>(out<FieldColourReference>()) =
      vision::FieldReference::from(in<ScanLineRegions>());
}

NAO_REGISTER_MODULE(FieldColourReferenceProvider);

}  // namespace nao::modules
