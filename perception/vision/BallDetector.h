#pragma once
// The ball (B-Human 2021, section 5: candidates from the scan-line regions, then a
// verifier; here a classical one of the ball's black-and-white pattern and outline).
//
// Candidates: non-field runs on the scan lines with something bright in them whose length
// fits the ball's expected image size at that place (a longer run, a ball touching a line or
// another white thing, gives one at each end), and the dark regions (a black patch) next to
// a bright one on a scan line: the seed is then inside the ball even where its white merges
// with a line, a foot or a shadow.
//
// Verification, with every threshold relative to this image and this ball:
// 1. Outline: rays from the seed find where the field starts (the field's colour, and at
//    least half its chroma for the luminance or its minimum chroma: the ball's white tinted
//    green by the light off the carpet is not field); a circle through the points
//    most of them agree with (robust to a line or a foot beside the ball) must have the
//    expected radius there. Where something other than field touches the ball, the outline
//    of its bright parts stands in.
// 2. Pattern: inside the circle, the black patches must be really dark relative to the
//    ball's own white (contrast) and be patches -- on rings about the centre, what is left
//    after the mean and a gradient across the ball (smooth shading of a robot's shoulder, a
//    shadow's edge) --, the white greyer than the field, no field colour.
// 3. Outline quality: the circle must be a real border all round -- where the field does not
//    start on it, the luminance must step across it. A robot's shoulder, an arm or a goal
//    post foot carries on across the fitted circle on a wide arc; a ball touching a line only
//    on a narrow one.
// 4. The evidence must add up: a weak pattern (a motion-blurred ball whose patches smear
//    into grey) is accepted only with a clean outline on all sides, wholly in the image, and
//    enough pixels for the shape to mean something; a partly hidden outline needs a clear
//    pattern; a ball mostly cut off by the image border a clear pattern and all of its
//    visible outline right.
// 5. A second opinion (BallClassifier.h) where a ball's colour is not its own: rejected only
//    for the field's colour inside it, a circle wholly in the image, at least
//    learnedMinRadiusPx big, whose hard figures hold (outline, size, field around, contrast
//    and dark share) may be accepted by a network trained on simulated, augmented patches
//    of the luminance alone. A ball lit from behind needs it: its shaded side takes the
//    carpet's tint, the sunlit carpet around it is as bright as its white, and no colour
//    step marks its outline.
// The position is where the centre's viewing ray meets the plane at ball-radius height.
// Obstacle boxes are not used: a ball often lies right in front of a robot (or the robot's
// own shoulder looms over it in the bottom camera), and the verifier tells a ball from a
// robot's parts.
#include <vector>

#include "perception/CameraModel.h"
#include "perception/OwnBody.h"
#include "perception/vision/BallClassifier.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct BallParams {
  double radius = 0.05;                               // m
  double minRadiusRatio = 0.85, maxRadiusRatio = 1.5;  // fitted / expected image radius
  double minOutline = 0.5;  // of the rays that stay in the image, those meeting the field on the circle
  int maxCandidates = 80;        // verified per image, those with a dark part first
  double maxFieldInside = 0.15;  // fraction of field-coloured samples inside the ball
  double minDarkInside = 0.08, maxDarkInside = 0.75;  // fraction of the black patches (and self-shadow)
  double maxGreyness = 0.6;      // mean chroma inside / mean chroma of the field around
  // The evidence (see the header comment): contrast = (white - dark) / white inside the ball,
  // support = fraction of the directions in which the circle is a real border, around =
  // fraction of field on a ring at 1.4 r.
  double minContrast = 0.3;    // any ball
  double clearContrast = 0.6;  // a clear pattern: black patches at most 0.4 of the white, and
  double clearEvidence = 1.5;  // contrast + (support + around) / 2 at least this, and
  double minPattern = 0.12;    // the dark parts patches, not shading: luminance left on rings
                               // inside after their mean and gradient, RMS / white
  double faintMinPattern = 0.06;  // a faint pattern: patches smeared, but still there ...
  double faintMinDark = 0.23, faintMaxDark = 0.5;  // ... covering a ball's share of it (about a third), ...
  double faintMinSupport = 0.85;  // an outline all round ...
  double faintMinAround = 0.75;   // ... on the field (a line may cross the ring) ...
  double faintMinRadiusPx = 6;    // ... and big enough in the image for its shape to tell
  // A ball cut by the image border (less than minVisible of it in the image): a clear pattern,
  // and all of the outline in the image on the circle, a border and on the field.
  double minVisible = 0.75;
  double cutMinContrast = 0.8, cutMinOutline = 0.85, cutMinSupport = 0.85;
  // The second opinion (null: none).
  const BallClassifier* classifier = nullptr;
  double minLearnedScore = 0.9;   // of -1..1
  double learnedSearchScore = 0.3;  // a circle scored at least this is searched about (see detectBall)
  // Asked only about a ball rejected for the field's colour inside it, up to this share: lit
  // from behind by the light off the carpet, its shaded side takes the carpet's tint, and the
  // colour the classical figures read is not its own. Elsewhere it is not asked: measured on
  // real images, it took a robot's shin on a lit field for a ball (0.97) -- the simulated
  // robots it learned "not a ball" from are simpler shapes than a real NAO's legs.
  double learnedMaxFieldInside = 0.5;
  double learnedMinRadiusPx = 6;  // smaller, the patches are a pixel or two
  // The robot's own body at the image's exposure (null: none): a circle centred on it is not
  // a ball, however ball-like (a hand, a foot's rounded shell).
  const OwnBody* ownBody = nullptr;
};

struct BallCandidate {
  Eigen::Vector2d seed = Eigen::Vector2d::Zero();
  double expectedRadius = 0;
  int priority = 0;           // 0: from a black patch or a run with a dark part, 1: otherwise
  bool alongVertical = true;  // found on a vertical scan line
  bool fromPatch = false;     // seeded by a dark region between bright ones
  bool fitted = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0;
  bool accepted = false;
  double score = 0;
  const char* rejectedBy = "";
  // The verifier's measurements (for debugging and tests).
  double contrast = 0, darkRatio = 0, fieldInside = 0, fieldAround = 0, bright = 0, satInside = 0, satAround = 0;
  double support = 0;  // fraction of the directions in which the circle is a real border
  double pattern = 0;  // luminance left on rings inside after mean and gradient, / white
  int inliers = 0, offImage = 0;
  bool byBrightOutline = false;  // outlined by its bright parts (something other than field beside it)
  double surround = 0;           // median luminance of the ring around the ball
  double learned = -2;           // the classifier's score (-2: not asked)
  bool byClassifier = false;     // accepted on the classifier's word
  std::vector<Eigen::Vector2d> outline;  // the outline points of the last fit (only when candidates are asked for)
};

// The best verified candidate; `candidates` (optional) receives all of them for debugging.
BallPercept detectBall(const CameraImage& image, const ScanLineRegions& regions, const FieldReference& field,
                       const ObstaclesPercept& obstacles, const CameraMatrix& cm, const BallParams& params = {},
                       std::vector<BallCandidate>* candidates = nullptr);

// The image radius a ball at this pixel would have (0 above the horizon).
double expectedBallRadius(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double radius);
// The ground position's covariance of a ball seen at `centre` (pixels) with `radiusPx`: the
// centre pixel's uncertainty (max(0.5, 0.08 radius) px) through the ray-plane intersection at
// the ball's centre height `radius`.
Eigen::Matrix2d ballCovariance(const CameraMatrix& cm, const Eigen::Vector2d& centre, double radiusPx, double radius);

}  // namespace nao::vision
