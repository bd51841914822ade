#include "perception/vision/BallClassifier.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <opencv2/core/utility.hpp>
#include <opencv2/ml.hpp>
#include <opencv2/objdetect.hpp>

#include "perception/vision/ColourTests.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"

namespace nao::vision {

namespace {
constexpr int kFeatures = kBallFeatures;
constexpr float kMinSpread = 4.0F;  // luminance steps: sensor noise on a flat patch is not a pattern
// OpenCV fills the network's matrices from the file without checking their lengths: a
// damaged file that still parses would leave weights uninitialised. So every list must have
// exactly the length the layer sizes give.
void checkModelShape(const std::string& path) {
  try {
    cv::FileStorage fs(path, cv::FileStorage::READ);
    const cv::FileNode net = fs["opencv_ml_ann_mlp"];
    if (!fs.isOpened() || net.empty()) throw Error(path, "not a ball classifier model (no opencv_ml_ann_mlp)");
    std::vector<int> layers;
    net["layer_sizes"] >> layers;
    if (layers.size() < 3 || layers.front() != kFeatures || layers.back() != 1 ||
        std::any_of(layers.begin(), layers.end(), [](int n) { return n < 1 || n > 100000; }))
      throw Error(path, "layer_sizes: must take " + std::to_string(kFeatures) + " inputs and give 1 output");
    auto expectLength = [&](const cv::FileNode& node, std::size_t n, const std::string& name) {
      if (!node.isSeq() || node.size() != n)
        throw Error(path, name + ": needs " + std::to_string(n) + " values, has " + std::to_string(node.size()));
    };
    expectLength(net["input_scale"], 2 * static_cast<std::size_t>(layers.front()), "input_scale");
    expectLength(net["output_scale"], 2, "output_scale");
    expectLength(net["inv_output_scale"], 2, "inv_output_scale");
    const cv::FileNode weights = net["weights"];
    if (!weights.isSeq() || weights.size() != layers.size() - 1)
      throw Error(path, "weights: needs " + std::to_string(layers.size() - 1) + " layers");
    for (std::size_t i = 1; i < layers.size(); ++i)
      expectLength(weights[static_cast<int>(i - 1)], static_cast<std::size_t>(layers[i - 1] + 1) * layers[i],
                   "weights[" + std::to_string(i - 1) + "]");
  } catch (const cv::Exception& e) {
    throw Error(path, "not a ball classifier model (OpenCV: " + e.msg.substr(0, e.msg.find('\n')) + ")");
  }
}

// OpenCV's thread count, restored however training ends.
struct SingleThreaded {
  int before = cv::getNumThreads();
  SingleThreaded() { cv::setNumThreads(1); }
  ~SingleThreaded() { cv::setNumThreads(before); }
  SingleThreaded(const SingleThreaded&) = delete;
  SingleThreaded& operator=(const SingleThreaded&) = delete;
};

}  // namespace

cv::Mat1f ballPatch(const CameraImage& image, const Eigen::Vector2d& centre, double radius) {
  cv::Mat1f patch(kBallPatchSize, kBallPatchSize, 0.0F);
  if (!image.valid() || image.width < 2 || image.height < 2 || !(radius > 0) || !std::isfinite(radius) ||
      !centre.allFinite())
    return patch;
  const double side = 2 * kBallPatchHalf * radius, cell = side / kBallPatchSize;
  const int k = static_cast<int>(std::clamp(std::ceil(cell / 1.5), 1.0, 4.0));  // samples per cell and axis
  const double x0 = centre.x() - side / 2, y0 = centre.y() - side / 2;
  for (int r = 0; r < kBallPatchSize; ++r)
    for (int c = 0; c < kBallPatchSize; ++c) {
      double sum = 0;
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j)
          sum += sampleLuminance(image, x0 + (c + (j + 0.5) / k) * cell, y0 + (r + (i + 0.5) / k) * cell);
      patch(r, c) = static_cast<float>(sum / (k * k));
    }
  return patch;
}

cv::Mat1f ballFeatures(const cv::Mat1f& patch) {
  // Normalised to its own mean and spread, then on the 8-bit scale the descriptor takes.
  cv::Scalar mean, spread;
  cv::meanStdDev(patch, mean, spread);
  cv::Mat1b u8;
  patch.convertTo(u8, CV_8U, 40.0 / std::max(spread[0], static_cast<double>(kMinSpread)),
                  128 - 40.0 * mean[0] / std::max(spread[0], static_cast<double>(kMinSpread)));
  // Cells of a quarter of the patch's side, blocks of two by two cells at half-block steps,
  // 9 orientation bins of unsigned gradients (a dark disc on bright carpet reads as a white
  // disc on dark). Each block is normalised on its own.
  static const cv::HOGDescriptor hog(cv::Size(kBallPatchSize, kBallPatchSize), cv::Size(10, 10), cv::Size(5, 5),
                                     cv::Size(5, 5), 9);
  std::vector<float> descriptor;
  hog.compute(u8, descriptor);
  cv::Mat1f row(1, static_cast<int>(descriptor.size()));
  std::copy(descriptor.begin(), descriptor.end(), row.begin());
  return row;
}

BallClassifier::BallClassifier() = default;
BallClassifier::~BallClassifier() = default;
BallClassifier::BallClassifier(BallClassifier&&) noexcept = default;
BallClassifier& BallClassifier::operator=(BallClassifier&&) noexcept = default;

bool BallClassifier::valid() const { return mlp_ && mlp_->isTrained(); }

BallClassifier BallClassifier::load(const std::string& path) {
  if (!std::ifstream(path)) throw Error(path, "cannot read the ball classifier model");
  checkModelShape(path);
  BallClassifier c;
  try {
    c.mlp_ = cv::ml::ANN_MLP::load(path);
  } catch (const cv::Exception& e) {
    throw Error(path, "not a ball classifier model (OpenCV: " + e.msg.substr(0, e.msg.find('\n')) + ")");
  }
  if (!c.mlp_ || !c.mlp_->isTrained()) throw Error(path, "not a ball classifier model (no trained network in it)");
  // Weights that are not numbers would give silent garbage (the shapes: checkModelShape).
  for (int l = 0; l < static_cast<int>(c.mlp_->getLayerSizes().total()) + 2; ++l) {
    const cv::Mat w = c.mlp_->getWeights(l);
    if (!w.empty() && !cv::checkRange(w)) throw Error(path, "weights: not finite in layer " + std::to_string(l));
  }
  return c;
}

void BallClassifier::save(const std::string& path) const {
  if (!valid()) throw Error(path, "no trained ball classifier to save");
  io::writeFileWith(path, [&](const std::string& temp) {
    try {
      mlp_->save(temp);
    } catch (const cv::Exception& e) {
      throw RunFailure(path, "cannot write the ball classifier model (" + e.err + ")");
    }
  });
}

BallClassifier BallClassifier::train(const cv::Mat1f& features, const std::vector<int>& labels,
                                     const TrainOptions& options) {
  if (features.rows != static_cast<int>(labels.size()) || features.cols != kFeatures || features.rows < 2)
    throw Error("train ball", "features and labels do not match");
  cv::Mat1f responses(features.rows, 1);
  for (int i = 0; i < features.rows; ++i) responses(i) = labels[i] ? 1.0F : -1.0F;
  BallClassifier c;
  c.mlp_ = cv::ml::ANN_MLP::create();
  c.mlp_->setLayerSizes(cv::Mat1i({3, 1}, {kFeatures, options.hidden, 1}).reshape(1, 1));
  c.mlp_->setActivationFunction(cv::ml::ANN_MLP::SIGMOID_SYM);
  c.mlp_->setTrainMethod(cv::ml::ANN_MLP::RPROP, 0.1, FLT_EPSILON);
  c.mlp_->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER + cv::TermCriteria::EPS, options.iterations, 1e-7));
  // The same samples, the same network: OpenCV starts every network from its own fixed random
  // state (not the global one), and one thread keeps the order of the sums fixed.
  bool ok = false;
  try {
    const SingleThreaded one;
    ok = c.mlp_->train(cv::ml::TrainData::create(features, cv::ml::ROW_SAMPLE, responses));
  } catch (const cv::Exception& e) {
    throw Error("train ball", "OpenCV: " + e.msg.substr(0, e.msg.find('\n')));
  }
  if (!ok || !c.valid()) throw Error("train ball", "the network did not train");
  return c;
}

double BallClassifier::score(const cv::Mat1f& features) const {
  if (!valid() || features.cols != kFeatures || features.rows != 1) return -1;
  cv::Mat out;
  mlp_->predict(features, out);
  const float s = out.at<float>(0, 0);
  return std::isfinite(s) ? std::clamp(static_cast<double>(s), -1.0, 1.0) : -1.0;
}

const BallClassifier& defaultBallClassifier() {
  static const BallClassifier classifier = BallClassifier::load(dataPath("models/vision/ball_classifier.yml"));
  return classifier;
}

}  // namespace nao::vision
