#include "scenarios/BallTraining.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "robot/Error.h"
#include "robot/ForwardKinematics.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/SceneBuilder.h"
#include "sim/World.h"
#include "scenarios/ProgramMetering.h"
#include "scenarios/RandomView.h"

namespace nao::sim {
namespace {

using vision::kBallPatchHalf;
using vision::kBallPatchSize;

constexpr double kDeg = M_PI / 180;
constexpr std::int32_t kSamplesMagic = 0x42534d31;  // the samples file's first int (native byte order)
constexpr int kOtherRobots = 3;

// A random light: any level and colour of the sweep's range, the sun from anywhere (low and
// behind the ball, it leaves the ball's visible side in its own shadow).
Lighting randomLighting(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0, 1);
  Lighting l;
  l.name = "random";
  l.intensity = 0.25 * std::pow(10.0, uni(rng));  // 0.25 .. 2.5, log-uniform
  l.temperature = 2700 + 3800 * uni(rng);
  l.shadows = uni(rng) < 0.5;
  l.elevation = 15 + 65 * uni(rng);
  l.azimuth = 360 * uni(rng);
  l.ambient = 0.15 + 0.3 * uni(rng);
  l.noise = 0.5 + 3.5 * uni(rng);
  return l;
}

}  // namespace

cv::Mat1f augmentBallPatch(const cv::Mat1f& raw, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0, 1);
  cv::Mat1f p = raw.clone();
  if (uni(rng) < 0.5) cv::flip(p, p, 1);
  if (uni(rng) < 0.35) {
    // Backlight: the disc (the circle asked about) darker, the rest brighter, clipped.
    const double inGain = 0.45 + 0.45 * uni(rng), outGain = 1.1 + 1.1 * uni(rng);
    const double c = (kBallPatchSize - 1) / 2.0, r = kBallPatchSize / (2 * kBallPatchHalf);
    for (int y = 0; y < p.rows; ++y)
      for (int x = 0; x < p.cols; ++x) {
        const double d = std::hypot(x - c, y - c);
        const double w = std::clamp(r + 1 - d, 0.0, 1.0);  // 1 inside, a pixel's soft edge
        p(y, x) = static_cast<float>(std::min(255.0, p(y, x) * (w * inGain + (1 - w) * outGain)));
      }
  }
  const double gamma = std::exp(std::log(1.7) * (2 * uni(rng) - 1));  // 0.6 .. 1.7
  const double gain = 0.5 + 1.1 * uni(rng);
  std::normal_distribution<double> noise(0, 4 * uni(rng));
  for (float& v : p) v = static_cast<float>(std::clamp(gain * 255 * std::pow(v / 255.0, gamma) + noise(rng), 0.0, 255.0));
  // A real camera's blur and lost resolution (motion, focus, compression).
  if (uni(rng) < 0.4) {
    const int small = kBallPatchSize / 2 + static_cast<int>(uni(rng) * kBallPatchSize / 2);
    cv::Mat1f d;
    cv::resize(p, d, cv::Size(small, small), 0, 0, cv::INTER_AREA);
    cv::resize(d, p, p.size(), 0, 0, cv::INTER_LINEAR);
  }
  if (uni(rng) < 0.4) cv::GaussianBlur(p, p, cv::Size(5, 5), 0.5 + 1.0 * uni(rng));
  return p;
}

void BallSamples::save(const std::string& path) const {
  std::string bytes;
  auto append = [&bytes](const void* data, std::size_t size) { bytes.append(static_cast<const char*>(data), size); };
  const std::int32_t header[3] = {kSamplesMagic, static_cast<std::int32_t>(patches.size()), frames};
  append(header, sizeof header);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const std::int32_t tags[2] = {labels[i], heldOut[i]};
    append(tags, sizeof tags);
    append(patches[i].ptr<float>(), sizeof(float) * patches[i].total());
  }
  io::writeFile(path, bytes);
}

BallSamples BallSamples::load(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path, "cannot read the ball samples");
  std::int32_t header[3] = {};
  f.read(reinterpret_cast<char*>(header), sizeof header);
  if (!f || header[0] != kSamplesMagic || header[1] < 0 || header[2] < 0) throw Error(path, "not a ball samples file");
  BallSamples s;
  s.frames = header[2];
  for (int i = 0; i < header[1]; ++i) {
    std::int32_t tags[2] = {};
    cv::Mat1f patch(kBallPatchSize, kBallPatchSize);
    f.read(reinterpret_cast<char*>(tags), sizeof tags);
    f.read(reinterpret_cast<char*>(patch.ptr<float>()), sizeof(float) * patch.total());
    if (!f) throw Error(path, "truncated at sample " + std::to_string(i));
    if ((tags[0] != 0 && tags[0] != 1) || (tags[1] != 0 && tags[1] != 1) || !cv::checkRange(patch, true, nullptr, 0, 256))
      throw Error(path, "sample " + std::to_string(i) + ": not a label, a split and a patch of luminance");
    s.patches.push_back(patch);
    s.labels.push_back(tags[0]);
    s.heldOut.push_back(tags[1]);
  }
  return s;
}

nlohmann::json BallTrainingResult::toJson() const {
  return {{"frames", frames},
          {"train", {{"balls", trainBalls}, {"others", trainOthers}, {"accuracy", trainAccuracy}}},
          {"held_out", {{"balls", heldOutBalls}, {"others", heldOutOthers}, {"ball_rate", heldOutBallRate},
                        {"false_rate", heldOutFalseRate}, {"curve", heldOutCurve}}}};
}

BallSamples renderBallSamples(const BallTrainingOptions& options) {
  if (options.scenes < 5) throw Error("--scenes", "needs at least 5 (every fifth is held out)");
  SceneSpec spec;
  spec.field = options.field;
  spec.robots.assign(1 + kOtherRobots, Eigen::Vector3d(0, 0, 0));
  for (int i = 1; i <= kOtherRobots; ++i) spec.robots[i] = Eigen::Vector3d(-4.0, 3.0 - i, 0);
  spec.balls = {Eigen::Vector3d(0, 0, kBallRadius)};
  World world(spec, options.seed);
  CameraRenderer renderer(world.model());
  const FieldModel& field = world.field();
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> uni(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };
  vision::BallParams params;
  params.radius = kBallRadius;

  BallSamples samples;
  const ProgramMetering metering(dataPath("config"));  // the exposure as the robot program meters it
  for (int scene = 0; scene < options.scenes; ++scene) {
    const bool hold = scene % 5 == 4;
    const RandomView view = randomView(field, 1.0, rng);
    const Eigen::Vector3d& pose = view.pose;
    const JointArray& posture = view.posture;
    const CameraCalibration& offsets = view.offsets;
    world.setMiscalibration(0, offsets);
    world.placeRobot(0, pose, posture);
    const double gaze = pose.z() + posture[HeadYaw];
    // Other robots in front of the observer, some close enough to stand beside the ball.
    for (int i = 1; i <= kOtherRobots; ++i) {
      const double bearing = gaze + uniform(-40, 40) * kDeg, dist = uniform(0.4, 4.0);
      const Eigen::Vector2d p = pose.head<2>() + dist * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
      JointArray other = StandController::standPosture();
      other[HeadYaw] = uniform(-60, 60) * kDeg;
      world.placeRobot(i, Eigen::Vector3d(p.x(), p.y(), uniform(-M_PI, M_PI)), other);
    }
    // The ball in front of the head, up to 5 m away, often close to one of the others' feet.
    Eigen::Vector2d ball;
    if (uni(rng) < 0.3) {
      const Eigen::Vector3d o = world.robotPose(1 + static_cast<int>(uni(rng) * kOtherRobots) % kOtherRobots);
      const double a = uniform(-M_PI, M_PI);
      ball = o.head<2>() + uniform(0.18, 0.35) * Eigen::Vector2d(std::cos(a), std::sin(a));
    } else {
      const double bearing = gaze + uniform(-35, 35) * kDeg, dist = 0.15 + 4.85 * std::pow(uni(rng), 0.8);
      ball = pose.head<2>() + dist * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
    }
    world.placeBall(0, Eigen::Vector3d(ball.x(), ball.y(), kBallRadius));

    const SensorFrame sensors = world.sensors(0);
    for (CameraId camera : {CameraId::Top, CameraId::Bottom}) {
      const CameraResolution res = world.cameraResolution(camera);
      const CameraIntrinsics in = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());
      const CameraMatrix cm = computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, camera, offsets, in);
      const ExposureWeights weights = metering(cm, sensors, offsets);
      std::vector<VisibleBall> balls;
      const std::vector<VisibleBall> allBalls = visibleFeatures(world, 0, camera, 1e9).balls;  // for the fits
      for (const VisibleBall& b : visibleFeatures(world, 0, camera, 6.0).balls)
        if (b.image.x() - b.radiusPx >= 0 && b.image.y() - b.radiusPx >= 0 && b.image.x() + b.radiusPx <= res.width &&
            b.image.y() + b.radiusPx <= res.height)
          balls.push_back(b);
      for (int k = 0; k < options.lightingsPerScene; ++k) {
        const Lighting lighting = options.lightings.empty()
                                      ? randomLighting(rng)
                                      : options.lightings[static_cast<std::size_t>(uni(rng) * options.lightings.size()) %
                                                          options.lightings.size()];
        std::mt19937_64 noiseRng(options.seed * 1000003 + scene * 17 + static_cast<int>(camera) * 5 + k);
        renderer.resetCameraSensors();  // each sample settled in its own light
        const CameraImage img = renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, camera),
                                                     res.width, res.height, lighting, camera, 0, noiseRng, weights);
        ++samples.frames;
        auto add = [&](const cv::Mat1f& patch, bool isBall) {
          samples.patches.push_back(patch);
          samples.labels.push_back(isBall ? 1 : 0);
          samples.heldOut.push_back(hold ? 1 : 0);
        };
        // The true ball as a fit would find it: moved and resized a little.
        for (const VisibleBall& b : balls) {
          if (b.radiusPx < params.learnedMinRadiusPx * 0.8) continue;
          for (int a = 0; a < options.augmentations; ++a) {
            const double dy = uniform(-1, 1);  // before dx: the order the committed model was trained with
            const Eigen::Vector2d c = b.image + 0.2 * b.radiusPx * Eigen::Vector2d(uniform(-1, 1), dy);
            add(vision::ballPatch(img, c, b.radiusPx * uniform(0.85, 1.25)), true);
          }
        }
        // The detector's own fitted circles.
        const FieldSegmentation seg = segmentField(img, cm);
        const vision::FieldReference ref = vision::FieldReference::from(seg.regions);
        std::vector<vision::BallCandidate> cands;
        vision::detectBall(img, seg.regions, ref, seg.obstacles, cm, params, &cands);
        int negatives = 0;
        for (const vision::BallCandidate& c : cands) {
          if (!c.fitted || c.radius < params.learnedMinRadiusPx * 0.8) continue;
          double nearest = 1e9, nearestR = 0;
          for (const VisibleBall& b : allBalls)
            if ((c.centre - b.image).norm() < nearest) nearest = (c.centre - b.image).norm(), nearestR = b.radiusPx;
          if (nearest < 0.5 * nearestR) {
            for (int a = 0; a < options.augmentations; ++a) add(vision::ballPatch(img, c.centre, c.radius), true);
          } else if (nearest > 1.5 * nearestR + 2 && negatives < options.maxNegativesPerFrame) {
            add(vision::ballPatch(img, c.centre, c.radius), false);
            ++negatives;
          }
        }
      }
    }
    if (options.progress) options.progress(scene + 1, options.scenes);
  }
  return samples;
}

BallTrainingResult trainBallClassifier(const BallTrainingOptions& options) {
  return trainBallClassifier(renderBallSamples(options), options);
}

BallTrainingResult trainBallClassifier(const BallSamples& samples, const BallTrainingOptions& options) {
  BallTrainingResult result;
  result.frames = samples.frames;
  // Augmented features.
  std::mt19937_64 augRng(options.seed * 7919 + 1);
  auto features = [&](int held, cv::Mat1f& x, std::vector<int>& y) {
    x.create(0, vision::kBallFeatures);
    for (std::size_t i = 0; i < samples.patches.size(); ++i) {
      if (samples.heldOut[i] != held) continue;
      x.push_back(vision::ballFeatures(augmentBallPatch(samples.patches[i], augRng)));
      y.push_back(samples.labels[i]);
    }
  };
  cv::Mat1f xTrain, xHeld;
  std::vector<int> yTrain, yHeld;
  features(0, xTrain, yTrain);
  features(1, xHeld, yHeld);
  for (int v : yTrain) (v ? result.trainBalls : result.trainOthers)++;
  for (int v : yHeld) (v ? result.heldOutBalls : result.heldOutOthers)++;
  if (result.trainBalls == 0 || result.trainOthers == 0) throw Error("train ball", "too few scenes: no ball or no other sample");
  result.classifier = vision::BallClassifier::train(xTrain, yTrain, options.network);

  int correct = 0;
  for (int i = 0; i < xTrain.rows; ++i) correct += (result.classifier.score(xTrain.row(i)) >= 0) == (yTrain[i] == 1);
  result.trainAccuracy = static_cast<double>(correct) / xTrain.rows;
  std::vector<double> heldScores(xHeld.rows);
  for (int i = 0; i < xHeld.rows; ++i) heldScores[i] = result.classifier.score(xHeld.row(i));
  auto rates = [&](double threshold) {
    int ballsHit = 0, falseHits = 0;
    for (int i = 0; i < xHeld.rows; ++i) (yHeld[i] ? ballsHit : falseHits) += heldScores[i] >= threshold;
    return std::array<double, 3>{threshold, result.heldOutBalls ? double(ballsHit) / result.heldOutBalls : 0,
                                 result.heldOutOthers ? double(falseHits) / result.heldOutOthers : 0};
  };
  const auto at = rates(options.threshold);
  result.heldOutBallRate = at[1];
  result.heldOutFalseRate = at[2];
  for (int i = 0; i <= 14; ++i) result.heldOutCurve.push_back(rates(-0.5 + 0.1 * i));
  return result;
}

}  // namespace nao::sim
