// libFuzzer target: the recorded camera matrix reader (perception/RecordedCameraMatrix.h), which
// perceive --camera-matrix and eval real take from users' files. Any input must either parse or
// throw nao::Error with a one-line message; anything else (a crash, another exception, a sanitizer
// report) is a finding, and so is a parsed matrix that is not a rotation or not finite.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "perception/RecordedCameraMatrix.h"
#include "robot/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const nao::RecordedCameraMatrix r =
        nao::RecordedCameraMatrix::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    const Eigen::Matrix3d R = r.matrix.pose.linear();
    if (!R.allFinite() || !r.matrix.pose.translation().allFinite()) std::abort();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6) std::abort();
    if (!(r.matrix.intrinsics.fx > 0 && r.matrix.intrinsics.fy > 0)) std::abort();
    for (const auto& l : r.lines)
      if (!l.a.allFinite() || !l.b.allFinite()) std::abort();
  } catch (const nao::Error& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
  return 0;
}
