// The ball classifier (perception/vision/BallClassifier.h) and its training
// (scenarios/BallTraining.h): the committed model against freshly rendered scenes it was not
// trained on (another seed), the features' independence of the light level, a deterministic
// training, and one-line errors for malformed model and sample files.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "perception/vision/BallClassifier.h"
#include "perception/vision/BallDetector.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/BallTraining.h"

namespace nao {
namespace {

using vision::BallClassifier;

std::string tempPath(const std::string& name) { return ::testing::TempDir() + name; }

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// Samples of scenes the committed model never saw (its training used seed 1).
const sim::BallSamples& freshSamples() {
  static const sim::BallSamples s = [] {
    sim::BallTrainingOptions o;
    o.scenes = 60;
    o.seed = 4242;
    o.lightingsPerScene = 1;
    o.augmentations = 1;
    return sim::renderBallSamples(o);
  }();
  return s;
}

TEST(BallClassifier, CommittedModelTellsFreshSimulatedBallsFromOtherThings) {
  const BallClassifier& model = vision::defaultBallClassifier();
  ASSERT_TRUE(model.valid());
  const sim::BallSamples& s = freshSamples();
  int balls = 0, ballsHit = 0, others = 0, othersHit = 0;
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    const bool hit = model.score(vision::ballFeatures(s.patches[i])) >= vision::BallParams{}.minLearnedScore;
    (s.labels[i] ? balls : others)++;
    (s.labels[i] ? ballsHit : othersHit) += hit;
  }
  std::printf("fresh scenes: %d/%d balls and %d/%d other circles scored as balls\n", ballsHit, balls, othersHit, others);
  ASSERT_GT(balls, 50);
  ASSERT_GT(others, 200);
  // The held-out rates of the training run: 0.85 of the balls, 0.1 % of the rest.
  EXPECT_GE(static_cast<double>(ballsHit) / balls, 0.75);
  EXPECT_LE(static_cast<double>(othersHit) / others, 0.01);
}

TEST(BallClassifier, FeaturesDoNotDependOnTheLightLevel) {
  const sim::BallSamples& s = freshSamples();
  ASSERT_FALSE(s.patches.empty());
  int compared = 0;
  for (std::size_t i = 0; i < s.patches.size() && compared < 50; ++i) {
    const cv::Mat1f& p = s.patches[i];
    double lo, hi;
    cv::minMaxLoc(p, &lo, &hi);
    if (hi > 200 || hi - lo < 20) continue;  // no clipping when brightened
    const cv::Mat1f a = vision::ballFeatures(p), b = vision::ballFeatures(p * 1.25F + 10.0F);
    EXPECT_LT(cv::norm(a - b) / cv::norm(a), 0.05) << "sample " << i;
    ++compared;
  }
  EXPECT_GT(compared, 20);
}

TEST(BallClassifier, TrainingIsDeterministicAndLearns) {
  sim::BallTrainingOptions o;
  o.scenes = 10;
  o.seed = 7;
  o.lightingsPerScene = 1;
  o.network.iterations = 30;
  const sim::BallSamples s = sim::renderBallSamples(o);
  const sim::BallTrainingResult a = sim::trainBallClassifier(s, o), b = sim::trainBallClassifier(s, o);
  ASSERT_TRUE(a.classifier.valid());
  EXPECT_GT(a.trainAccuracy, 0.9);  // what it was shown, it learned
  const std::string pa = tempPath("model_a.yml"), pb = tempPath("model_b.yml");
  a.classifier.save(pa);
  b.classifier.save(pb);
  EXPECT_EQ(readFile(pa), readFile(pb));
  // Saved and loaded, the same scores.
  const BallClassifier loaded = BallClassifier::load(pa);
  for (std::size_t i = 0; i < s.patches.size(); i += 7) {
    const cv::Mat1f f = vision::ballFeatures(s.patches[i]);
    EXPECT_NEAR(loaded.score(f), a.classifier.score(f), 1e-5);
  }
  // The samples file round-trips.
  const std::string ps = tempPath("samples.bin");
  s.save(ps);
  const sim::BallSamples r = sim::BallSamples::load(ps);
  ASSERT_EQ(r.patches.size(), s.patches.size());
  EXPECT_EQ(r.labels, s.labels);
  EXPECT_EQ(cv::norm(r.patches.back() - s.patches.back()), 0.0);
}

// A bad file is a one-line Error naming it, never a crash or a silently wrong model.
void expectLoadError(const std::string& path, const std::string& what, const std::string& says = "") {
  try {
    BallClassifier::load(path);
    ADD_FAILURE() << what << ": loaded";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << what << ": " << m;
    EXPECT_NE(m.find(says), std::string::npos) << what << ": " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << what << ": " << m;
  }
}

TEST(BallClassifier, MalformedModelFilesGiveOneLineErrors) {
  expectLoadError(tempPath("missing.yml"), "missing");
  const std::string good = readFile(dataPath("models/vision/ball_classifier.yml"));
  ASSERT_GT(good.size(), 1000U);
  const std::string p = tempPath("bad.yml");
  writeFile(p, "not a model at all");
  expectLoadError(p, "garbage");
  writeFile(p, "%YAML:1.0\n---\nopencv_ml_ann_mlp:\n   format: 3\n");
  expectLoadError(p, "empty network");
  for (double keep : {0.1, 0.5, 0.9}) {
    writeFile(p, good.substr(0, static_cast<std::size_t>(keep * good.size())));
    expectLoadError(p, "truncated at " + std::to_string(keep));
  }
  // Another network's shape.
  std::string other = good;
  const auto at = other.find("layer_sizes");
  ASSERT_NE(at, std::string::npos);
  const auto num = other.find("324", at);
  ASSERT_NE(num, std::string::npos);
  other.replace(num, 3, "325");
  writeFile(p, other);
  expectLoadError(p, "layer sizes", "layer_sizes");
  // One weight fewer, the file still well-formed YAML (OpenCV alone would leave one
  // uninitialised).
  std::string shorter = good;
  const auto w0 = shorter.find("weights");
  ASSERT_NE(w0, std::string::npos);
  const auto line = shorter.find("\n         - ", w0);
  ASSERT_NE(line, std::string::npos);
  shorter.erase(line, shorter.find('\n', line + 1) - line);
  writeFile(p, shorter);
  expectLoadError(p, "a weight missing", "weights[0]: needs");
  // A weight that is not a number.
  std::string nan = good;
  const auto w = nan.find("weights");
  ASSERT_NE(w, std::string::npos);
  const auto first = nan.find("\n         - ", w) + std::string("\n         - ").size();
  nan.replace(first, nan.find('\n', first) - first, ".nan");
  writeFile(p, nan);
  expectLoadError(p, "nan weight", "not finite");
}

TEST(BallClassifier, MalformedSampleFilesGiveOneLineErrors) {
  const std::string p = tempPath("bad_samples.bin");
  writeFile(p, "BSM");
  EXPECT_THROW(sim::BallSamples::load(p), Error);
  sim::BallSamples s;
  s.patches.push_back(cv::Mat1f(vision::kBallPatchSize, vision::kBallPatchSize, 100.0F));
  s.labels.push_back(1);
  s.heldOut.push_back(0);
  s.save(p);
  const std::string good = readFile(p);
  writeFile(p, good.substr(0, good.size() - 10));
  EXPECT_THROW(sim::BallSamples::load(p), Error);
  std::string badLabel = good;
  badLabel[12] = 5;
  writeFile(p, badLabel);
  EXPECT_THROW(sim::BallSamples::load(p), Error);
}

}  // namespace
}  // namespace nao
