#pragma once
// Training the ball classifier (perception/vision/BallClassifier.h) from simulated images:
// random scenes like `eval perception`'s (the observer anywhere on the field, its head
// anywhere in range, a ball mostly in front of it) plus a few other robots near it, whose
// feet, arms and shoulders are what a ball candidate most often turns out to be. Each scene is
// rendered by both cameras under lighting presets of the sweep.
//
// Samples are what the detector will ask about: the circles its outline fit finds (a ball
// when it is within half a radius of the true ball's image, not a ball when it is far from
// every ball) and the true ball's circle, moved and resized a little as a fit would. Every
// sample is augmented the same way for both classes -- mirrored, gamma, gain with clipping,
// noise, blur, and "backlight": the disc darkened and its surroundings brightened towards
// clipping, as a ball in its own shadow on sunlit carpet --, so what tells the classes apart
// is the shape, not the light. Every fifth scene is held out to measure the result.
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "perception/vision/BallClassifier.h"
#include "sim/Lighting.h"

namespace nao::sim {

struct BallTrainingOptions {
  int scenes = 1500;
  std::uint64_t seed = 1;
  FieldDimensions field;
  std::vector<Lighting> lightings;  // each scene is rendered under lightingsPerScene of them
  int lightingsPerScene = 2;       // 1..5 (the sensor noise's seed spaces them by 5)
  int augmentations = 3;            // copies of each ball sample (the non-balls: 1)
  int maxNegativesPerFrame = 12;
  double threshold = 0.9;           // the score the held-out rates are reported at
  vision::BallClassifier::TrainOptions network;
  std::function<void(int done, int total)> progress;
};

struct BallTrainingResult {
  vision::BallClassifier classifier;
  int trainBalls = 0, trainOthers = 0, heldOutBalls = 0, heldOutOthers = 0, frames = 0;
  double trainAccuracy = 0;
  double heldOutBallRate = 0;   // held-out balls scored >= threshold
  double heldOutFalseRate = 0;  // held-out non-balls scored >= threshold
  // (threshold, ball rate, false rate) at thresholds -0.5 .. 0.9
  std::vector<std::array<double, 3>> heldOutCurve;
  nlohmann::json toJson() const;
};

// The rendered samples before augmentation: raw luminance patches (vision::ballPatch).
struct BallSamples {
  std::vector<cv::Mat1f> patches;
  std::vector<int> labels;  // 1 ball, 0 not
  std::vector<int> heldOut; // 1: from a held-out scene
  int frames = 0;
  void save(const std::string& path) const;
  static BallSamples load(const std::string& path);  // a malformed file is an Error naming it
};

// One augmented copy of a raw patch; the same operations for balls and non-balls.
cv::Mat1f augmentBallPatch(const cv::Mat1f& raw, std::mt19937_64& rng);

BallSamples renderBallSamples(const BallTrainingOptions& options);
// Augments and trains; options.seed and options.network as for the whole run.
BallTrainingResult trainBallClassifier(const BallSamples& samples, const BallTrainingOptions& options);
BallTrainingResult trainBallClassifier(const BallTrainingOptions& options);

}  // namespace nao::sim
