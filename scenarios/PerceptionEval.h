#pragma once
// How well does the vision see what is there? Random robot poses and head angles over the
// whole field, both cameras, a random ball, small injected camera offsets that the camera
// model is told, balls on the field, each scene rendered under every lighting preset of the sweep (intensity,
// colour temperature, hard shadows, sensor noise). The truth comes from the simulator's
// field model and state (ground truth with ray-cast occlusion), never from the detector.
//
// Figures (design.md): lines.recall (true lines with >= 0.5 m visible within 4 m that some
// detection matches: within 5 deg and 10 cm on the ground), lines.precision (detections that
// match a field line), circle.detection_rate (frames with >= half of the circle in view
// within 3 m where it is found within 0.3 m), ball.recall_3m / recall_5m (balls in view,
// >= 75 % of the disc on the image, found within max(0.3 m, 20 % of the distance)),
// ball.false_per_frame (ball percepts that match no ball), ball.median_error_ratio
// (position error / distance of the found balls).
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "controllers/modules/OracleVision.h"
#include "perception/FieldDimensions.h"
#include "robot/Debug.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct PerceptionEvalOptions {
  int trials = 300;                 // scenes; each is rendered by both cameras under every lighting
  std::uint64_t seed = 1;
  FieldDimensions field;
  std::vector<Lighting> lightings;  // empty: the default preset
  VenueChoice venue;                // trial t's look: venue.forSeed(seed + t) (none: the diagram)
  double maxOffsetDeg = 1.0;        // injected camera offsets, uniform in +-this, told to the model
  double ballProbability = 0.85;    // of a scene having a ball placed in front of the robot
  std::string imagesDir;            // non-empty: annotated frames (every imagesEvery-th scene)
  int imagesEvery = 25;
  std::string failuresDir;          // non-empty: annotated frames with a miss or a false detection
  DebugChannels* debug = nullptr;   // line_rejects, eval_lines, eval_balls, timing (not owned); null: none
  std::function<void(int done, int total)> progress;
  // "vision": render and run the camera pipeline; "oracle": no rendering, the fast percept
  // mode's OracleVision with `oracle` as its error model (what the test compares).
  std::string percepts = "vision";
  modules::OracleVision::Params oracle;
  bool fitOracle = false;  // collect OracleFit (fitting needs the vision)
};

// What the fast percept mode's error model is fitted from: per distance bin (the oracle's
// bins), how many of the features the oracle would offer the vision found, how far off it
// was, and its false percepts. The truth here is the oracle's own view of each frame
// (sim/OracleCamera.h), so the rates fit exactly what the oracle draws from.
struct OracleFit {
  std::vector<double> bins;
  struct Rate {
    std::vector<int> seen, found;
  };
  Rate ball, linesLong, linesShort, circle, penaltyMark;
  // |pixel error| of the found balls: over the radius for near (large) balls, in pixels for
  // far (small) ones, where the pixel grid bounds the error.
  std::vector<double> ballErrorPerRadius, ballErrorPxSmall;
  std::vector<double> lineErrorPx;         // ends of the found lines, across the true line
  std::vector<double> circleErrorM, penaltyMarkErrorM;
  int frames = 0, falseBalls = 0, falseLines = 0, falseCircles = 0, falsePenaltyMarks = 0;

  explicit OracleFit(std::vector<double> distanceBins = {});
  void add(const OracleFit& o);
  // The error model these figures give (empty bins take the bin before's rate).
  modules::OracleVision::Params params(const modules::OracleVision::Params& defaults, const std::string& fittedBy) const;
};

struct PerceptionFigures {
  int frames = 0;
  int trueLines = 0, trueLinesFound = 0;
  int detectedLines = 0, detectedLinesMatched = 0;
  int circleFrames = 0, circleFound = 0, circleFalse = 0;
  int balls3 = 0, found3 = 0, balls5 = 0, found5 = 0;
  int ballPercepts = 0, falseBalls = 0;
  std::vector<double> ballErrorRatios;
  int intersections = 0, intersectionsCorrect = 0;  // position within 0.3 m and the same type
  int penaltyMarks = 0, penaltyMarksCorrect = 0;
  int penaltyMarkFrames = 0, penaltyMarkFound = 0;  // a cross in view within 3 m, wholly in the image
  std::vector<double> imageNoise;  // each rendered frame's luma noise (ImageDenoiser)
  int blurredFrames = 0;           // frames the vision read blurred for their noise
  double lineRecall() const { return trueLines ? double(trueLinesFound) / trueLines : 1; }
  double linePrecision() const { return detectedLines ? double(detectedLinesMatched) / detectedLines : 1; }
  double circleRate() const { return circleFrames ? double(circleFound) / circleFrames : 1; }
  double ballRecall3() const { return balls3 ? double(found3) / balls3 : 1; }
  double ballRecall5() const { return balls5 ? double(found5) / balls5 : 1; }
  double falseBallsPerFrame() const { return frames ? double(falseBalls) / frames : 0; }
  double medianBallErrorRatio() const;
  void add(const PerceptionFigures& o);
  nlohmann::json toJson() const;
};

struct PerceptionEvalResult {
  PerceptionFigures all;
  std::map<std::string, PerceptionFigures> byLighting;
  std::vector<std::string> lightingOrder;
  std::map<std::string, PerceptionFigures> byVenue;  // by the venue look's name
  std::vector<double> perceptionMs;  // the camera pipeline's total per frame
  std::optional<OracleFit> oracleFit;  // with fitOracle
  nlohmann::json toJson() const;
};

PerceptionEvalResult evaluatePerception(const PerceptionEvalOptions& options);

}  // namespace nao::sim
