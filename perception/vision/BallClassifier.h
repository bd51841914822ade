#pragma once
// The ball verifier's second opinion: a small neural network (OpenCV's multi-layer
// perceptron) that looks at the luminance around a fitted ball circle and says how much it
// looks like a ball. Trained inside this project (`nao-soccer train ball`,
// scenarios/BallTraining.h) from simulated images with augmentation; the weights are
// models/vision/ball_classifier.yml.
//
// The features are HOG (histograms of oriented gradients, OpenCV's): measured on real NAO
// images, a network on the normalised pixels themselves found only 3 of 7 real balls that the
// classical verifier finds, a random forest 3, a network on HOG 6 (2026-12-02).
//
// Why a learned part at all: the classical verifier (BallDetector.h) reads the ball from
// colour and luminance steps, and a ball lit from behind has neither -- its shaded side
// takes the carpet's tint and sits darker than the sunlit carpet around it. What still
// marks it is the shape: a round disc with dark patches in it. The network sees only the
// patch normalised to its own mean and spread, so light level and colour cast do not
// matter; the detector asks it only about circles the outline fit already found at the
// expected size on the field, and only where the classical evidence fell short.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "robot/CameraImage.h"

namespace cv::ml {
class ANN_MLP;
}

namespace nao::vision {

// The patch: a square of side 2 * kBallPatchHalf * r about the circle's centre, sampled on a
// kBallPatchSize x kBallPatchSize grid (each cell the mean of a few bilinear samples, so a
// big ball is not aliased). Raw luminance, 0..255; parts off the image repeat the border.
constexpr int kBallPatchSize = 20;
constexpr double kBallPatchHalf = 1.4;
cv::Mat1f ballPatch(const CameraImage& image, const Eigen::Vector2d& centre, double radius);

// The network's input, one row: histograms of the gradients' orientations (HOG) on the
// patch normalised to zero mean and unit spread -- the shape of the edges, not the light.
constexpr int kBallFeatures = 324;
cv::Mat1f ballFeatures(const cv::Mat1f& patch);

class BallClassifier {
 public:
  BallClassifier();
  ~BallClassifier();
  BallClassifier(BallClassifier&&) noexcept;
  BallClassifier& operator=(BallClassifier&&) noexcept;

  // Reads a model written by save(); a missing or malformed file is an Error naming it.
  static BallClassifier load(const std::string& path);
  void save(const std::string& path) const;

  struct TrainOptions {
    int hidden = 16;          // neurons in the one hidden layer
    int iterations = 200;     // RPROP epochs (full batch)
  };
  // features: one row per sample (ballFeatures); labels: 1 ball, 0 not. The same samples give
  // the same network (OpenCV's own fixed initial weights, one thread).
  static BallClassifier train(const cv::Mat1f& features, const std::vector<int>& labels, const TrainOptions& options);

  bool valid() const;
  // -1 (surely not a ball) .. 1 (surely a ball).
  double score(const cv::Mat1f& features) const;
  double score(const CameraImage& image, const Eigen::Vector2d& centre, double radius) const {
    return score(ballFeatures(ballPatch(image, centre, radius)));
  }

 private:
  cv::Ptr<cv::ml::ANN_MLP> mlp_;
};

// The committed model, models/vision/ball_classifier.yml under dataPath(), loaded once.
const BallClassifier& defaultBallClassifier();

}  // namespace nao::vision
