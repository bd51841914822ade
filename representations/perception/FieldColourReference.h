#pragma once
// This image's field colour and white point in the units the white and field tests use
// (vision::FieldReference, perception/vision/ColourTests.h), from the cut scan-line regions.
#include "perception/vision/ColourTests.h"

namespace nao {

struct FieldColourReference : vision::FieldReference {};

}  // namespace nao
