// The renderer and the robot program's camera model agree: line corners found in rendered
// images lie where the camera model projects them (issue: simulated NAO, acceptance 2).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "scenarios/CameraAgreement.h"

namespace nao::sim {

TEST(CameraAgreement, RenderedCornersMatchTheCameraModel) {
  AgreementOptions o;
  o.poses = std::getenv("NAO_TEST_QUICK") ? 15 : 50;
  o.seed = 7;
  const AgreementResult r = measureCameraAgreement(o);
  int perSetting[2][2] = {{0, 0}, {0, 0}};
  for (const auto& c : r.corners) perSetting[c.offsets][static_cast<int>(c.camera)]++;
  std::printf("trials %d (with corners %d), corners %zu (top %d/%d, bottom %d/%d without/with offsets), "
              "corner RMS %.3f px, max %.3f px; edge samples %zu, median |err| %.3f px\n",
              r.trials, r.trialsWithCorners, r.corners.size(), perSetting[0][0], perSetting[1][0],
              perSetting[0][1], perSetting[1][1], r.cornerRmsPx, r.cornerMaxPx, r.edgeErrorsPx.size(),
              r.edgeMedianAbsPx);
  EXPECT_EQ(r.trials, 4 * o.poses);
  // Every camera/offset combination must contribute real measurements, not just a few.
  for (int off = 0; off < 2; ++off)
    for (int cam = 0; cam < 2; ++cam) EXPECT_GE(perSetting[off][cam], o.poses / 2) << off << " " << cam;
  EXPECT_GE(r.trialsWithCorners, r.trials / 2);
  EXPECT_LE(r.cornerRmsPx, 0.5);
  EXPECT_LE(r.cornerMaxPx, 1.0);
  EXPECT_LE(r.edgeMedianAbsPx, 0.3);
}

// The measurement itself can fail: a model that ignores the injected offsets does not agree.
TEST(CameraAgreement, DetectsAModelThatIgnoresTheOffsets) {
  AgreementOptions o;
  o.poses = 6;
  o.seed = 11;
  o.maxOffsetDeg = 3;
  o.modelIgnoresOffsets = true;
  const AgreementResult r = measureCameraAgreement(o);
  ASSERT_FALSE(r.corners.empty());
  EXPECT_GT(r.cornerMaxPx, 3.0);
}

}  // namespace nao::sim
