// The image's own noise (perception/vision/Denoise.h) against the noise the test adds itself,
// the box blur against plain averages, and ImageDenoiser in the camera pipeline: on a dim,
// noisy image of painted lines the regions read from the blurred copy lie where the paint is.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "perception/vision/CameraPipeline.h"
#include "perception/vision/Denoise.h"
#include "perception/vision/modules/ImageDenoiser.h"
#include "perception/vision/modules/ScanLineRegionProvider.h"
#include "tests/support/ModuleHarness.h"
#include "tests/support/StandingCamera.h"
#include "tests/support/SyntheticScene.h"

namespace nao {
namespace {

using testing::ModuleHarness;

// The luma's standard deviation from RGB noise of standard deviation sigma in each channel
// (BT.601 weights, independent channels).
double lumaSigma(double rgbSigma) {
  return rgbSigma * std::sqrt(0.299 * 0.299 + 0.587 * 0.587 + 0.114 * 0.114);
}

// Two lines crossing in front of the robot.
bool paint(const Eigen::Vector2d& g) { return std::abs(g.x() - 1.5) < 0.025 || std::abs(g.y()) < 0.025; }

CameraImage scene(double gain, double rgbNoise) {
  test::Light light;
  light.gain = gain;
  light.noise = rgbNoise;
  return test::syntheticImage(test::standingCamera(0, 15), {}, paint, light);
}

CameraImage flat(int value) {
  CameraImage image;
  image.width = 64, image.height = 48;
  image.yuyv.assign(64 * 48 * 2, static_cast<std::uint8_t>(value));
  return image;
}

TEST(LumaNoise, MeasuresTheNoiseAddedBesideLinesAndEdges) {
  for (double sigma : {4.0, 10.0, 18.0}) {
    const double truth = lumaSigma(sigma);
    EXPECT_NEAR(lumaNoise(scene(1.0, sigma)), truth, 0.2 * truth) << "rgb sigma " << sigma;
  }
  // A clean image of sharp lines: the edges alone do not read as noise.
  EXPECT_LT(lumaNoise(scene(1.0, 0.0)), 1.0);
  EXPECT_EQ(lumaNoise(CameraImage{}), 0.0);
}

TEST(BoxBlur, AveragesOverTheBoxAndLeavesAFlatImageAlone) {
  CameraImage blurred;
  boxBlur(flat(77), 2, blurred);
  EXPECT_EQ(blurred.yuyv, flat(77).yuyv);
  // One bright pixel spreads evenly over its 5 x 5 box (inside the image), nothing beyond.
  CameraImage dot = flat(0);
  dot.yuyv[(20 * 64 + 30) * 2] = 250;
  boxBlur(dot, 2, blurred);
  for (int y = 16; y <= 24; ++y)
    for (int x = 26; x <= 34; ++x) {
      const bool inBox = std::abs(x - 30) <= 2 && std::abs(y - 20) <= 2;
      EXPECT_EQ(blurred.y(x, y), inBox ? 10 : 0) << x << "," << y;
    }
  // Noise of standard deviation s over a flat grey: about s / 5 after a 5 x 5 box.
  CameraImage noisy = flat(100);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 12);
  for (std::size_t i = 0; i < noisy.yuyv.size(); i += 2) noisy.yuyv[i] = roundToByte(100 + n(rng));
  boxBlur(noisy, 2, blurred);
  double sum = 0, sum2 = 0;
  int count = 0;
  for (int y = 2; y < 46; ++y)
    for (int x = 2; x < 62; ++x, ++count) sum += blurred.y(x, y), sum2 += blurred.y(x, y) * blurred.y(x, y);
  const double mean = sum / count, sd = std::sqrt(sum2 / count - mean * mean);
  EXPECT_NEAR(mean, 100, 0.7);
  EXPECT_LT(sd, 12.0 / 5 * 1.3);
  EXPECT_GT(sd, 12.0 / 5 * 0.7);
}

TEST(ImageDenoiser, BlursOnlyANoisyImage) {
  ModuleHarness h = ModuleHarness::make<modules::ImageDenoiser>(ModuleContext{});
  const CameraImage clean = scene(1.0, 3.0);
  h.fix(clean).run();
  const DenoisedImage& d = h.get<DenoisedImage>();
  EXPECT_EQ(d.radius, 0);
  EXPECT_LT(d.noise, 4.0);
  EXPECT_EQ(&d.image(clean), &clean) << "an ordinary image is read as it came";
  const CameraImage noisy = scene(0.35, 18.0);
  h.fix(noisy).run();
  const DenoisedImage& n = h.get<DenoisedImage>();
  EXPECT_GT(n.noise, 9.0);
  EXPECT_GT(n.radius, 0);
  EXPECT_TRUE(n.image(noisy).valid());
  EXPECT_NE(&n.image(noisy), &noisy);
}

// Balls 2.5 to 4 m away in a dim, noisy image (gain 4 at the camera's longest exposure looks
// like this): found by the pipeline as configured, which reads the blurred copy, and by the same
// pipeline with the blur switched off. Truth: where the test put each ball.
TEST(ImageDenoiser, FindsSmallBallsInTheNoise) {
  const CameraMatrix cm = test::standingCamera(0, 12);
  test::Light light;
  light.gain = 0.25;
  light.noise = 25;
  DenoiseParams off;
  off.enabled = false;
  CameraPipelineConfig plain;
  plain.params["ImageDenoiser"] = off;
  int found = 0, foundPlain = 0, balls = 0;
  for (double x : {2.5, 3.0, 3.5, 4.0})
    for (double y : {-0.6, 0.0, 0.5}) {
      const Eigen::Vector3d centre(x, y, test::kSyntheticBallRadius);
      const CameraImage image = test::syntheticImage(
          cm, {{centre, test::kSyntheticBallRadius, test::soccerBall(Eigen::Matrix3d::Identity())}}, paint, light);
      const auto seenAt = [&](const CameraPipelineConfig& config) {
        CameraPipeline pipeline(image.camera, VisionGeometry{}, config);
        const BallPercept& b = pipeline.process(image, cm).ball;
        return b.seen && (b.position - centre.head<2>()).norm() < 0.1 * x;
      };
      ++balls;
      found += seenAt(CameraPipelineConfig{});
      foundPlain += seenAt(plain);
    }
  std::printf("balls found: %d of %d blurred, %d plain\n", found, balls, foundPlain);
  EXPECT_GE(found, foundPlain + 4);
  EXPECT_GE(found, 0.6 * balls);
}

}  // namespace
}  // namespace nao
