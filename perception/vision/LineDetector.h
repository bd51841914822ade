#pragma once
// Field lines from the colour-segmented scan lines (B-Human 2021, section 5.2): white regions
// on vertical scan lines (for lines running across the image) and on horizontal scan lines
// (for lines running up it) that are as thick as a field line there and not inside an
// obstacle or the ball become line spots; spots on neighbouring scan lines chain into
// segments; segments of one line are merged (by regression of their spots) only where the
// merged line passes the white test: sample points on the line, comparison points on both
// sides, the sample brighter and less saturated, the comparison point field.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "perception/CameraModel.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct LineParams {
  double lineWidth = 0.05;        // m, SPL
  double circleRadius = 0.75;     // m: short pieces that bend like the centre circle are no lines
  double maxThicknessFactor = 3;  // a white run up to this many expected line widths (+2 px) is a spot
  // A run wider than this many expected widths (+2 px) is measured again at half its contrast:
  // centre and width. The regions of a soft-edged line include its ramps (real frames at 2-5
  // m: runs of 9-13 px on a 5 px line), which moved the spots and broke their chains.
  double halfContrastFactor = 1;
  double mergeWhiteRatio = 0.75;  // of the white test's pairs along a gap two segments are merged across
  // Two pieces are tried as one line when each one's ends lie within this many times the spot
  // tolerance of the other's line; the merged fit then keeps every spot within the tolerance.
  // A piece of three spots extrapolates its direction badly: at 1.0 the goal-box side line of
  // real frames stayed in pieces shorter than minLengthM (docs/vision/real/README.md).
  double mergeReach = 1.5;
  double mergeKinkDeg = 3;        // see fitLines: pieces of a bent line
  int mergeKinkSpots = 8;
  double lineWhiteRatio = 0.6;    // of the white test's pairs along a whole line to report it
  int minSpots = 4;               // per reported line
  // A line with fewer spots than this whose pixels do not refine (see refineAcross) must be
  // about as thick as a line: its median run, turned across it, at most this fraction of
  // twice the expected width (+1.5 px); on real images such lines were a robot's arm, twice
  // as wide as a line there.
  int unrefinedSpots = 6;
  double unrefinedThickness = 0.6;
  int minSpotsRefined = 4;        // the same with a sub-pixel refinement (3-spot lines were mostly object edges on real images)
  double minLengthM = 0.25;       // per reported line (on the ground)
  // A candidate with fewer than minSpots spots is followed along its own pixels beyond its ends
  // (profiles across it every growStepPx, at most growMaxSteps per end; 0: never) and counts as
  // a line when at least minGrown centres continue it: the scan grid crosses a short line far
  // away only a few times (docs/vision/real/README.md).
  double growStepPx = 3;
  int growMaxSteps = 40;
  int minGrown = 4;
  double maxDistanceM = 5;        // lines whose nearest point is farther are not reported
  double maxAngleSigmaDeg = 2;    // lines whose direction on the ground is less certain are not reported
  double spotSigmaPx = 0.5;       // least position error of a line spot (px)
  double refinedSigmaPx = 0.25;   // least position error of a sub-pixel centre across the line (px)
};

// The expected image size of a short stretch `len` of the ground at a pixel: along the
// ground direction away from the camera (mostly vertical in the image) and across it.
struct GroundScale {
  bool valid = false;
  Eigen::Vector2d ground = Eigen::Vector2d::Zero();  // robot frame
  double alongPx = 0, acrossPx = 0;
};
GroundScale groundScale(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double len);

struct LineSpot {
  Eigen::Vector2d image = Eigen::Vector2d::Zero();   // centre of the white region
  Eigen::Vector2d ground = Eigen::Vector2d::Zero();  // robot frame
  double thicknessPx = 0;                            // the region's length
  double expectedPx = 0;                             // a line's thickness there along the scan line
  bool vertical = true;                              // from a vertical scan line
  int scan = 0;                                      // index of its scan line
};

// A chain of spots on consecutive scan lines of one direction (indices into spots).
struct SpotChain {
  std::vector<int> spots;
  bool vertical = true;
  int chain = -1;  // for a segment: the chain it was split from
};

struct LineCandidates {
  std::vector<LineSpot> spots;
  std::vector<SpotChain> chains;    // as found: straight or curved (circle)
  std::vector<SpotChain> segments;  // chains split where they bend: straight in the image
};

// Spots, chains and straight segments (from regions the field reference calls white).
// `ball` (optional): its disc is not a line.
LineCandidates findLineCandidates(const CameraImage& image, const ScanLineRegions& regions,
                                  const FieldReference& field, const ObstaclesPercept& obstacles, const CameraMatrix& cm,
                                  const LineParams& params = {}, const BallPercept* ball = nullptr);

// The white test along an image segment: the fraction of sample/comparison pairs that pass
// (sample points every ~`spacingPx`, at most maxSamples; comparison points beside the line at
// a distance that follows the line's expected width). Samples off the image or inside an
// obstacle do not count, nor do comparison points on other paint (a crossing line);
// paintBesideFraction receives the fraction of samples with paint beside them. nullopt when
// no pair counts.
std::optional<double> whiteRatio(const CameraImage& image, const FieldReference& field, const CameraMatrix& cm,
                                 const Eigen::Vector2d& from, const Eigen::Vector2d& to, double lineWidth,
                                 const ObstaclesPercept* obstacles = nullptr, double spacingPx = 6,
                                 int maxSamples = 24, double* paintBesideFraction = nullptr);

// Why a merged candidate was not reported (for debugging and tests).
struct RejectedLine {
  Eigen::Vector2d imageFrom, imageTo;
  int spots = 0;
  const char* reason = "";
  double value = 0;
};

// Merges the straight segments into lines (skipping segments whose spots are mostly
// `excluded`, e.g. on the centre circle) and keeps the lines that pass the white test.
std::vector<LinesPercept::Line> fitLines(const LineCandidates& candidates, const std::vector<char>& excludedSpots,
                                         const CameraImage& image, const FieldReference& field,
                                         const ObstaclesPercept& obstacles, const CameraMatrix& cm,
                                         const LineParams& params = {},
                                         std::vector<RejectedLine>* rejected = nullptr);

// Total least squares line through points: (centroid, unit direction).
std::pair<Eigen::Vector2d, Eigen::Vector2d> fitLineTls(const std::vector<Eigen::Vector2d>& points);

}  // namespace nao::vision
