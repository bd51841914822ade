#pragma once
// Self-localization: a few extended Kalman filters over the pose (x, y, theta), each a
// hypothesis with a score, managed by a small hypothesis layer (merging, pruning, selection with
// hysteresis) and fed by sensor resetting from unambiguous field features. docs/modeling.md.
//
// Per cycle: `update(input)` applies the odometry step (process noise growing with distance
// and turn), then the percepts of each camera image: field lines (perpendicular distance and
// angle), intersections by type (L/T/X), the centre circle, the penalty marks; a hypothesis that
// puts field lines where the image surely showed ground and none was seen fits it less
// (negative information, FieldPercepts::view). Feature
// combinations (centre circle + halfway line, penalty mark + penalty-area line, a typed corner
// with its orientation) give candidate poses, verified against all percepts of the image,
// clustered over time; a cluster seen often enough that no hypothesis explains becomes a new
// hypothesis (kidnap, lost). The field's point symmetry is never guessed: hypotheses start from
// the game situation (`resetTo...`), and a candidate is taken in whichever of its two mirror
// images is closer to the current estimate.
#include <cstdint>
#include <utility>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "perception/modeling/ModelingTypes.h"

namespace nao {
namespace modeling_detail {
struct Element;  // one usable percept (SelfLocator.cpp)
}

class SelfLocator {
 public:
  struct Params {
    // Odometry (process) noise, standard deviation of one step.
    double odomTransPerMetre = 0.20;  // m of translation error per m walked
    double odomTransPerRad = 0.02;    // m of translation error per rad turned
    double odomRotPerRad = 0.10;      // rad of heading error per rad turned
    double odomRotPerMetre = 0.10;    // rad of heading error per m walked
    double odomTransFloor = 0.0005;   // m per step (standing still, the feet still slip)
    double odomRotFloor = 0.0005;     // rad per step
    double maxOdometryStep = 0.5;     // m: a larger step is absurd and skipped
    double maxOdometryTurn = 1.0;     // rad: a larger turn is absurd and skipped

    // Association (a percept fits a field element when inside both the metric gate, widened by
    // the hypothesis' own uncertainty, and the chi-square gate).
    double lineGate = 0.4;             // m, corridor about the model line
    double lineAngleGate = 0.35;       // rad
    double maxAngleWidening = 0.15;    // rad: the most a line's angle gate widens with the hypothesis' heading sigma
    double lineEndMargin = 0.4;        // m a measured segment may reach past the model line's ends
    double minLineLength = 0.15;       // m; shorter measured lines are not used
    double intersectionGate = 0.5;     // m
    double circleGate = 0.8;           // m
    double penaltyMarkGate = 0.75;     // m
    double chi2Gate = 13.8;            // Mahalanobis^2 gate, 2 dof (99.9 %)
    double maxPerceptDistance = 7.0;   // m: farther or non-finite percepts are skipped

    // Negative information: a hypothesis that puts at least negativeMinExpected m of field line
    // inside an image's view (FieldPercepts::view) fits that image only as far as the lines it
    // matched there reach negativeDetectRate of that length (a fit of 0 for none). The rate
    // allows for lines the vision misses (far, dark, smeared) and for occlusion.
    double negativeMinExpected = 1.0;  // m of field line in view
    double negativeDetectRate = 0.35;  // share of it that a right hypothesis sees matched
    double negativeMinArc = 1.5;       // m of the centre circle's arc in view: ...
    double negativeMissedCircle = 0.3; // ... the image's fit when no circle fits

    // Hypotheses.
    int maxHypotheses = 12;
    double scoreRate = 0.1;            // per image: weight of the newest fit in a score
    double mergeDistance = 0.25;       // m: closer hypotheses are merged ...
    double mergeAngle = 0.15;          // rad: ... when their headings are this close, too
    double pruneMargin = 0.3;          // a hypothesis this far below the best score is dropped ...
    int pruneMinAge = 20;              // ... once it has seen this many images
    double switchMargin = 0.08;        // another hypothesis is selected when it scores this much more

    // Sensor resetting.
    double clusterDistance = 0.5;      // m: a candidate joins a cluster this close ...
    double clusterAngle = 0.3;         // rad: ... in position and heading
    double clusterLifetime = 10;       // s without a new candidate before a cluster is forgotten
    int maxClusters = 8;
    int clusterMinObservations = 5;    // candidates before a cluster can become a hypothesis
    double resetDistance = 1.0;        // m: ... when no hypothesis is this close ...
    double resetAngle = 0.52;          // rad: ... in position and heading (30 deg)
    double resetScore = 0.3;           // score of a hypothesis added by resetting
    double candidateMinSupport = 0.8;  // share of an image's percepts that must fit a candidate
    int candidateMinPercepts = 3;      // and at least this many
    double maxGyroForFeatures = 0.87;  // rad/s: no candidates while the body turns faster (50 deg/s)
    double mirrorAngleWeight = 0.2;    // m per rad, when comparing a candidate's two mirror images

    // Validity.
    double validQuality = 0.5;         // score at least ...
    double validSigmaTranslation = 0.3;  // m, and the position's sigma at most ...
    double validSigmaRotation = 0.35;  // rad, and the heading's

    // The game situation's prior: a hypothesis from resetToSidelineEntry / resetToPenaltyReturn
    // that leaves the half the robot was put on (by more than the margin) within its first
    // images is dropped: near the halfway line a wide hypothesis of the other side line could
    // otherwise slide onto the mirror image of the truth, which fits every percept as well.
    // Likewise, of two such hypotheses that became each other's mirror image (within these), the
    // one farther out of the half is dropped.
    int situationPriorImages = 150;    // images (both cameras count)
    double situationPriorMargin = 0.1; // m beyond the halfway line
    double situationMirrorDistance = 1.5;  // m
    double situationMirrorAngle = 0.6;     // rad

    // A hypothesis farther than this outside the field lines is dropped: no robot stands there
    // (the carpet's border is 0.7 m), and one that slid there fits what little it would see.
    double offFieldMargin = 0.7;       // m

    // Initial spreads (sigma x m, y m, theta rad).
    Eigen::Vector3d sidelineSigma{0.75, 0.15, 0.3};
    Eigen::Vector3d penaltyReturnSigma{0.5, 0.2, 0.3};
  };

  struct Hypothesis {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // x, y, theta (field frame)
    Eigen::Matrix3d cov = Eigen::Matrix3d::Identity();
    double score = 0.5;
    int age = 0;  // images seen
    // While age < Params::situationPriorImages: the field x it must stay within (the game situation).
    double xMin = -std::numeric_limits<double>::infinity(), xMax = std::numeric_limits<double>::infinity();
    std::uint64_t id = 0;
  };

  // What happened to the inputs so far (for debug channels and tests).
  struct Stats {
    int skippedOdometry = 0;     // non-finite or absurd odometry steps
    int skippedPercepts = 0;     // non-finite, absurd or too far percept elements
    int skippedSets = 0;         // percept sets with a non-finite time
    int skippedResets = 0;       // resetTo() with a non-finite pose or sigma
    int candidates = 0;          // verified feature candidates
    int resets = 0;              // hypotheses added by sensor resetting
    int reinitialisations = 0;   // the filter lost all hypotheses and started again
    int priorViolations = 0;     // hypotheses dropped for leaving the game situation's half
    int offField = 0;            // hypotheses dropped for leaving the field and its border
    long negativeImages = 0;     // hypothesis-images whose fit negative information lowered
  };

  explicit SelfLocator(const FieldModel& field) : SelfLocator(field, Params()) {}
  SelfLocator(const FieldModel& field, const Params& params);

  // Initial hypotheses from the game situation. The robot walks in at a side line of its own
  // half (ownHalf) or the opponent's, facing the field, somewhere along the half.
  void resetToSidelineEntry(bool ownHalf = true);
  // A penalised robot returns at either side line level with its own penalty mark, facing in.
  void resetToPenaltyReturn();
  // One hypothesis about a known pose with the given sigmas (m, m, rad).
  void resetTo(const Pose2& pose, const Eigen::Vector3d& sigmas);

  // One cognition cycle: odometry, then each camera's percepts. Returns the estimate.
  RobotPose update(const LocalizationInput& input);
  // The parts of update(), for callers with other cadences.
  bool applyOdometry(const Pose2& delta);  // false: skipped as non-finite or absurd
  void applyPercepts(const FieldPercepts& percepts, double gyroZ = 0);

  RobotPose estimate() const;
  const std::vector<Hypothesis>& hypotheses() const { return hyps_; }
  const Stats& stats() const { return stats_; }
  const Params& params() const { return params_; }
  const FieldModel& field() const { return field_; }

  // Candidate poses from the feature combinations in one percept set, each verified against
  // the set's other percepts. Each is one of its two mirror images (the caller picks).
  std::vector<Pose2> featureCandidates(const FieldPercepts& percepts) const;
  // The length (m) of field line (straight lines and the centre circle's arc) a robot at `pose`
  // would have inside the view polygon (robot frame); `circle`: the arc's part of it.
  double expectedLineLength(const Eigen::Vector3d& pose, const std::vector<Eigen::Vector2d>& view,
                            double* circle = nullptr) const;
  // (x, y, theta) -> (-x, -y, theta + pi): the field's point symmetry.
  static Pose2 mirror(const Pose2& p);

 private:
  struct Cluster {
    Eigen::Vector3d mean;  // running mean (theta by the mean of the angle differences)
    int count = 0;
    double lastTime = 0;
  };
  struct ModelCorner {
    FieldIntersection::Type type;
    Eigen::Vector2d position;
    std::vector<Eigen::Vector2d> arms;  // unit directions of the lines leaving it
  };

  void startOver(const std::vector<Eigen::Vector3d>& means, const Eigen::Vector3d& sigmas, double xMin, double xMax);
  void addHypothesis(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov, double score);
  using Elements = std::vector<modeling_detail::Element>;
  // The EKF update by the image's elements; true when the centre circle was among those it matched.
  bool updateHypothesis(Hypothesis& h, const Elements& els, double& fit, int& used, double& matchedLength) const;
  bool supports(const Eigen::Vector3d& pose, const Elements& els) const;
  std::vector<Pose2> candidatesFrom(const FieldPercepts& percepts, const Elements& els) const;
  void addCandidate(const Pose2& candidate, double time);
  void manageHypotheses();
  void reinitialiseIfEmpty();
  const Hypothesis* best() const;

  FieldModel field_;
  Params params_;
  std::vector<Hypothesis> hyps_;
  std::vector<Cluster> clusters_;
  std::vector<ModelCorner> corners_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> circleChords_;  // the centre circle as a polygon
  std::uint64_t nextId_ = 1;
  std::uint64_t selectedId_ = 0;
  Eigen::Vector3d lastGood_ = Eigen::Vector3d::Zero();
  double time_ = 0;
  Stats stats_;
};

}  // namespace nao
