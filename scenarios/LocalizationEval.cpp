#include "scenarios/LocalizationEval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <random>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "perception/calibration/CalibrationStore.h"
#include "representations/behavior/BehaviorCommand.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"
#include "robot/Error.h"
#include "scenarios/EvalRows.h"
#include "scenarios/WalkEval.h"
#include "sim/CameraRenderer.h"
#include "sim/OracleCamera.h"
#include "sim/SceneBuilder.h"
#include "sim/SimBackend.h"
#include "sim/Turf.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kSettle = 2.0;            // s before the first score (the filter starts from the game situation)
constexpr double kArrivedDistance = 0.10;  // m, truth: a leg ends when the robot stands there ...
constexpr double kArrivedAngle = 10 * kDeg;
constexpr double kArrivedHold = 0.5;  // ... this long
constexpr double kLegTimeout = 12;    // s: or after this long
constexpr double kStandBefore = 1.5;  // s standing before a kidnap or a kick
constexpr double kRecoveredDistance = 0.20;  // m
constexpr double kRecoveredHold = 1.0;       // s the estimate must stay within it
constexpr double kRecoveryLimit = 10;        // s
constexpr double kBallStill = 0.01;          // m/s: the true ball lies still below this speed
constexpr double kFalseBallDistance = 0.5;   // m from every true ball
constexpr double kRollingEndAfter = 1.0;     // s after the kick: the model's end position scored then
constexpr double kRollMin = 1, kRollMax = 4;  // m: the rolls scored (the acceptance's kicks of 1-4 m)
constexpr double kRollLimit = 8;             // s after the kick at most

const char* kindName(LocalizationTrialKind k) {
  switch (k) {
    case LocalizationTrialKind::Walk: return "walk";
    case LocalizationTrialKind::Kidnap: return "kidnap";
    case LocalizationTrialKind::Rolling: return "rolling";
  }
  return "walk";
}

LocalizationTrialKind kindOf(const LocalizationEvalOptions& o, std::uint64_t seed) {
  if (o.kidnapEvery > 0 && seed % static_cast<std::uint64_t>(o.kidnapEvery) == static_cast<std::uint64_t>(o.kidnapEvery - 1))
    return LocalizationTrialKind::Kidnap;
  if (o.rollEvery > 0 && seed % static_cast<std::uint64_t>(o.rollEvery) == 1 % static_cast<std::uint64_t>(o.rollEvery))
    return LocalizationTrialKind::Rolling;
  return LocalizationTrialKind::Walk;
}

const Lighting& lightingOf(const LocalizationEvalOptions& o, std::uint64_t seed) {
  return o.lightings[seed % o.lightings.size()];
}

// Rows store their samples rounded (0.1 mm, 0.001 deg): the aggregate is always computed from
// the stored values, so a resumed run and an uninterrupted one agree to the bit.
double rounded(double v, double scale) { return std::round(v * scale) / scale; }

const char* binOf(double distance) {
  if (distance < 2) return "0-2";
  if (distance < 4) return "2-4";
  if (distance < 6) return "4-6";
  return nullptr;
}

}  // namespace

nlohmann::json localizationEvalSettings(const LocalizationEvalOptions& o) {
  return {{"randomize", o.randomize},
          {"residual_deg", o.randomize ? o.residualDeg : 0.0},
          {"walk_s", o.walkSeconds},
          {"kidnap_every", o.kidnapEvery},
          {"roll_every", o.rollEvery},
          {"percepts", o.oracle ? "oracle" : "vision"},
          {"field", {{"length", o.field.length}, {"width", o.field.width}}}};
}

nlohmann::json runLocalizationTrial(const LocalizationEvalOptions& o, std::uint64_t seed) {
  using Clock = std::chrono::steady_clock;
  const auto wallStart = Clock::now();
  const LocalizationTrialKind kind = kindOf(o, seed);
  const Lighting& lighting = lightingOf(o, seed);
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ULL + 0x2545f4914f6cdd1dULL);
  std::uniform_real_distribution<double> u01(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * u01(rng); };
  const double halfL = o.field.length / 2, halfW = o.field.width / 2;
  auto inside = [&](const Eigen::Vector2d& p, double margin) {
    return std::abs(p.x()) <= halfL - margin && std::abs(p.y()) <= halfW - margin;
  };

  // The game situation: entering at a side line of the own half (x < 0), facing the field.
  const double side = u01(rng) < 0.5 ? -1.0 : 1.0;
  const Eigen::Vector3d start(uniform(-halfL + 0.5, -0.5), side * halfW, -side * M_PI / 2);
  Eigen::Vector2d ball;
  do {
    const double y = uniform(-halfW + 0.3, halfW - 0.3);  // before x: the order of the committed figures
    ball = Eigen::Vector2d(uniform(-halfL + 0.3, halfL - 0.3), y);
  } while ((ball - start.head<2>()).norm() < 0.7);
  // The scripted walk: field poses 1-3 m apart, away from the ball.
  std::vector<Pose2> legs;
  Eigen::Vector2d from = start.head<2>();
  while (legs.size() < 4) {
    const double a = uniform(-M_PI, M_PI), d = uniform(1.0, 3.0);
    const Eigen::Vector2d to = from + d * Eigen::Vector2d(std::cos(a), std::sin(a));
    if (!inside(to, 0.7) || (to - ball).norm() < 0.6) continue;
    legs.emplace_back(to.x(), to.y(), uniform(-M_PI, M_PI));
    from = to;
  }

  SceneSpec spec;
  spec.field = o.field;
  spec.robots = {start};
  spec.balls = {Eigen::Vector3d(ball.x(), ball.y(), kBallRadius)};
  World world(spec, seed);
  CameraCalibration told;
  nlohmann::json robotJson = {{"randomized", o.randomize}};
  if (o.randomize) {
    AppliedVariation v = applyVariation(world, 0, RobotVariation{}, seed);
    // The head's two joints: their offsets are what a robot's joint and camera calibration
    // remove (a pitch offset is a camera pitch offset to the calibration; a yaw offset would be
    // an uncalibratable heading error). The legs, arms and masses stay foreign.
    v.jointOffsets[HeadYaw] = v.jointOffsets[HeadPitch] = 0;
    world.setJointOffsets(0, v.jointOffsets);
    v.maxJointOffset = 0;
    for (double a : v.jointOffsets) v.maxJointOffset = std::max(v.maxJointOffset, std::abs(a));
    std::array<double, 6> injected{}, known{};
    for (int i = 0; i < 6; ++i) {
      injected[i] = uniform(-3, 3) * kDeg;
      known[i] = injected[i] + uniform(-o.residualDeg, o.residualDeg) * kDeg;
    }
    world.setMiscalibration(0, CameraCalibration::fromArray(injected));
    told = CameraCalibration::fromArray(known);
    robotJson["mass_kg"] = rounded(v.totalMass, 1e4);
    robotJson["friction"] = rounded(v.friction, 1e4);
    robotJson["max_joint_offset_deg"] = rounded(v.maxJointOffset / kDeg, 1e3);
    nlohmann::json inj, err;
    for (int i = 0; i < 6; ++i) {
      inj[CameraCalibration::kNames[i]] = rounded(injected[i] / kDeg, 1e3);
      err[CameraCalibration::kNames[i]] = rounded((known[i] - injected[i]) / kDeg, 1e3);
    }
    robotJson["camera_offsets_deg"] = inj;
    robotJson["calibration_error_deg"] = err;
  }
  world.placeRobot(0, start, StandController::standPosture());

  std::optional<CameraRenderer> renderer;  // the fast percept mode renders nothing
  std::mt19937_64 noiseRng(seed ^ 0x9e3779b97f4a7c15ULL);
  SimBackend backend(world, 0, true);
  if (o.oracle) {
    backend.setImageSource([&](CameraId cam, double, const ExposureWeights&) { return oracleImage(world, 0, cam); });
  } else {
    renderer.emplace(world.model());
    backend.setImageSource([&](CameraId cam, double time, const ExposureWeights& metering) {
      const CameraResolution res = world.cameraResolution(cam);
      return renderer->renderImage(world.model(), world.data(), world.cameraIndex(0, cam), res.width, res.height,
                                   lighting, cam, time, noiseRng, metering);
    });
  }
  RobotProgramConfig config;
  if (o.oracle) config.providers["CameraPercepts"] = "OracleVision";
  config.calibration = o.randomize ? told : calibration::CalibrationStore().offsetsFor(backend.robotInfo().headId);
  config.headId = backend.robotInfo().headId;
  config.field = o.field;
  config.goTo = legs.front();
  config.debug = o.debug;
  RobotProgram program(config);

  // --- the scorer (reads the truth; the robot program never does) ---
  auto estimateNow = [&](const Blackboard& cognition) {
    RobotPose pose = cognition.read<RobotPose>();
    pose.pose = pose.pose * (pose.odometry.inverse() * program.blackboard().read<Odometry>().pose);
    return pose;
  };
  auto ballNow = [&](const Blackboard& cognition) {
    BallModel b = cognition.read<BallModel>();
    const Pose2 delta = cognition.read<RobotPose>().odometry.inverse() * program.blackboard().read<Odometry>().pose;
    b.position = delta.inverse() * b.position;
    b.endPosition = delta.inverse() * b.endPosition;
    return b;
  };
  auto truePose = [&] {
    const Eigen::Vector3d r = world.robotPose(0);
    return Pose2(r.x(), r.y(), r.z());
  };

  enum class Phase { Walk, Stand, Kidnapped, Rolling } phase = Phase::Walk;
  bool ballMoved = false;  // from the referee's placing the ball until the robot has it (or the kick)
  std::vector<double> positionErrors, headingErrors;
  std::map<std::string, std::vector<double>> ballStatic{{"0-2", {}}, {"2-4", {}}, {"4-6", {}}};
  long runs = 0, scored = 0, mirrored = 0, ballClaims = 0, falseBalls = 0;
  // Kidnap: when, the first cognition run inside the radius since the last one outside.
  double kidnapTime = -1, insideSince = -1, recoveryS = -1, errorAfterKidnap = -1;
  bool recovered = false;
  // Rolling: when the kick was, the model's end position (field frame) at kRollingEndAfter.
  double kickTime = -1;
  std::optional<Eigen::Vector2d> modelEnd;
  bool modelEndRolling = false;

  program.setCognitionObserver([&](const CameraImage& image, const Blackboard& cognition) {
    if (world.time() < kSettle || !cognition.has<RobotPose>()) return;
    const RobotPose pose = estimateNow(cognition);
    const Pose2 truth = truePose();
    const double positionError = (pose.pose.translation() - truth.translation()).norm();
    if (phase == Phase::Kidnapped) {
      if (errorAfterKidnap < 0) errorAfterKidnap = positionError;
      if (recovered) return;
      const double t = world.time();
      if (positionError < kRecoveredDistance) {
        if (insideSince < 0) insideSince = t;
        if (insideSince - kidnapTime <= kRecoveryLimit && t - insideSince >= kRecoveredHold) {
          recovered = true;
          recoveryS = insideSince - kidnapTime;
        }
      } else {
        insideSince = -1;
      }
      return;
    }
    ++runs;
    if (pose.valid) {
      ++scored;
      positionErrors.push_back(rounded(positionError, 1e4));
      headingErrors.push_back(rounded(std::abs(Pose2::wrap(pose.pose.theta - truth.theta)) / kDeg, 1e3));
      const Eigen::Vector2d mirror = -truth.translation();
      if ((pose.pose.translation() - mirror).norm() < positionError) ++mirrored;
    }
    if (!cognition.has<BallModel>() || ballMoved) return;  // the referee just moved it: no model could know
    const BallModel b = ballNow(cognition);
    const Eigen::Vector2d trueBall = truth.inverse() * Eigen::Vector2d(world.ballPosition(0).head<2>());
    const bool still = world.ballVelocity(0).head<2>().norm() < kBallStill;
    if (b.valid && !b.lost && still)
      if (const char* bin = binOf(trueBall.norm())) ballStatic[bin].push_back(rounded((b.position - trueBall).norm(), 1e4));
    if (b.valid && b.seenTime == image.timestamp) {
      ++ballClaims;
      if ((b.position - trueBall).norm() > kFalseBallDistance) ++falseBalls;
    }
    if (phase == Phase::Rolling && !modelEnd && kickTime >= 0 && world.time() - kickTime >= kRollingEndAfter && b.valid &&
        !b.lost) {
      modelEnd = truth * b.endPosition;
      modelEndRolling = b.rolling;
    }
  });

  int falls = 0;
  bool wasFallen = false;
  auto cycle = [&] {
    if (!program.cycle(backend)) throw Error("simulation", backend.stopReason());
    const bool fallen = program.blackboard().read<FallState>().fallen;
    falls += fallen && !wasFallen;
    wasFallen = fallen;
  };
  auto runFor = [&](double seconds, const std::function<bool()>& done = {}) {
    const double end = world.time() + seconds;
    while (world.time() + 1e-9 < end) {
      cycle();
      if (done && done()) return;
    }
  };

  // The scripted walk: each leg until the robot stands at its target (truth) or the leg's time
  // runs out; the operator then gives the next target.
  const double walkEnd = world.time() + o.walkSeconds;
  int legsReached = 0, legsGiven = 0;
  for (const Pose2& leg : legs) {
    if (world.time() >= walkEnd) break;
    program.blackboard().write<BehaviorCommand>().goTo = leg;
    ++legsGiven;
    double arrivedSince = -1;
    bool reached = false;
    runFor(std::min(kLegTimeout, walkEnd - world.time()), [&] {
      const Pose2 t = truePose();
      const bool there = (t.translation() - leg.translation()).norm() < kArrivedDistance &&
                         std::abs(Pose2::wrap(t.theta - leg.theta)) < kArrivedAngle;
      if (!there) arrivedSince = -1;
      else if (arrivedSince < 0) arrivedSince = world.time();
      reached = there && world.time() - arrivedSince >= kArrivedHold;
      return reached;
    });
    legsReached += reached;
  }
  if (world.time() < walkEnd) runFor(walkEnd - world.time());

  nlohmann::json row = {{"seed", seed}, {"kind", kindName(kind)}, {"lighting", lighting.name},
                        {"settings", localizationEvalSettings(o)}, {"robot", robotJson}};
  row["legs"] = {{"given", legsGiven}, {"reached", legsReached}};
  row["start"] = {rounded(start.x(), 1e3), rounded(start.y(), 1e3), rounded(start.z() / kDeg, 1e1)};

  if (kind == LocalizationTrialKind::Kidnap) {
    // The referee lifts the standing robot and sets it down elsewhere; nobody tells the filter.
    phase = Phase::Stand;
    program.blackboard().write<BehaviorCommand>().goTo.reset();
    runFor(kStandBefore);
    const Pose2 before = truePose();
    const double errorBefore = (estimateNow(program.cognitionBoard()).pose.translation() - before.translation()).norm();
    // 1-3 m and 45-180 deg away, on the field, off the ball, and clearly nearer the old pose
    // than its point mirror (the field's symmetry leaves that case undecidable by design).
    Eigen::Vector3d to;
    for (int attempt = 0; attempt < 200; ++attempt) {
      const double a = uniform(-M_PI, M_PI), d = uniform(1.0, 3.0);
      const double turn = (u01(rng) < 0.5 ? -1 : 1) * uniform(45, 180) * kDeg;
      const Eigen::Vector2d p = before.translation() + d * Eigen::Vector2d(std::cos(a), std::sin(a));
      to = Eigen::Vector3d(p.x(), p.y(), Pose2::wrap(before.theta + turn));
      const Eigen::Vector2d b = world.ballPosition(0).head<2>();
      if (inside(p, 0.3) && (p - b).norm() > 0.4 && (p - before.translation()).norm() + 1.0 < (-p - before.translation()).norm())
        break;
    }
    world.placeRobot(0, to, StandController::standPosture());
    phase = Phase::Kidnapped;
    kidnapTime = world.time();
    runFor(kRecoveryLimit + kRecoveredHold, [&] { return recovered; });
    const Pose2 after = truePose();
    row["kidnap"] = {{"recovered", recovered},
                     {"recovery_s", recovered ? nlohmann::json(rounded(recoveryS, 1e3)) : nlohmann::json()},
                     {"error_before_m", rounded(errorBefore, 1e4)},
                     {"error_after_m", rounded(errorAfterKidnap, 1e4)},  // the first image after it
                     {"distance_m", rounded((Eigen::Vector2d(to.x(), to.y()) - before.translation()).norm(), 1e4)},
                     {"from", {rounded(before.x, 1e3), rounded(before.y, 1e3), rounded(before.theta / kDeg, 1e1)}},
                     {"to", {rounded(to.x(), 1e3), rounded(to.y(), 1e3), rounded(to.z() / kDeg, 1e1)}},
                     {"turn_deg", rounded(std::abs(Pose2::wrap(to.z() - before.theta)) / kDeg, 1e3)},
                     {"error_end_m", rounded((estimateNow(program.cognitionBoard()).pose.translation() - after.translation()).norm(), 1e4)},
                     {"mirrored_end", (estimateNow(program.cognitionBoard()).pose.translation() + after.translation()).norm() <
                                          (estimateNow(program.cognitionBoard()).pose.translation() - after.translation()).norm()}};
  } else if (kind == LocalizationTrialKind::Rolling) {
    // The robot stands; the referee rolls a ball in where its top camera looks, 1.2-2 m away
    // (its behaviour searches features, not balls, while it knows none), and kicks it 1-4 m
    // away from the robot or across its view once the robot has it, staying on the field.
    phase = Phase::Stand;
    program.blackboard().write<BehaviorCommand>().goTo.reset();
    runFor(kStandBefore);
    const Pose2 at = truePose();
    const Eigen::Vector3d axis = world.cameraPose(0, CameraId::Top).linear().col(0);
    const double bearing = std::atan2(axis.y(), axis.x());
    Eigen::Vector2d place = Eigen::Vector2d::Zero(), velocity = Eigen::Vector2d::Zero();
    double roll = 0;
    for (int attempt = 0; attempt < 200; ++attempt) {
      const double b = bearing + uniform(-10, 10) * kDeg, d = uniform(1.2, 2.0);
      place = at.translation() + d * Eigen::Vector2d(std::cos(b), std::sin(b));
      roll = uniform(1.0, 4.0);
      const double direction = b + uniform(-90, 90) * kDeg;
      const Eigen::Vector2d dir(std::cos(direction), std::sin(direction));
      velocity = std::sqrt(2 * kBallRollingDeceleration * roll) * dir;  // rolls of 1-4 m
      if (inside(place, 0.3) && inside(place + roll * dir, 0.3)) break;
    }
    world.placeBall(0, Eigen::Vector3d(place.x(), place.y(), kBallRadius));
    ballMoved = true;
    // The kicker waits (up to 6 s) until the robot has the ball: its model, seen in the last
    // 0.1 s, within 0.3 m of where the ball lies.
    double ready = -1;
    runFor(6.0, [&] {
      if (!program.cognitionBoard().has<BallModel>()) return false;
      const BallModel b = ballNow(program.cognitionBoard());
      const bool has = b.valid && !b.lost && b.seenTime > world.time() - 0.1 && (truePose() * b.position - place).norm() < 0.3;
      if (has && ready < 0) ready = world.time();
      return has && world.time() - ready >= 0.5;
    });
    phase = Phase::Rolling;
    ballMoved = false;
    kickTime = world.time();
    world.placeBall(0, Eigen::Vector3d(place.x(), place.y(), kBallRadius), Eigen::Vector3d(velocity.x(), velocity.y(), 0));
    runFor(kRollLimit, [&] {
      return world.time() - kickTime > kRollingEndAfter + 0.2 && world.ballVelocity(0).head<2>().norm() < kBallStill;
    });
    const Eigen::Vector2d stop = world.ballPosition(0).head<2>();
    row["rolling"] = {{"speed_m_s", rounded(velocity.norm(), 1e4)},
                      {"roll_m", rounded((stop - place).norm(), 1e4)},
                      {"stopped", world.ballVelocity(0).head<2>().norm() < kBallStill},
                      {"end_error_m", modelEnd ? nlohmann::json(rounded((*modelEnd - stop).norm(), 1e4)) : nlohmann::json()},
                      {"model_rolling", modelEndRolling},
                      {"ball_seen_before_kick", ready >= 0}};
  }
  row["position_error_m"] = positionErrors;
  row["heading_error_deg"] = headingErrors;
  row["runs"] = runs;
  row["valid"] = scored;
  row["mirrored"] = mirrored;
  row["ball_static_error_m"] = ballStatic;
  row["ball_claims"] = ballClaims;
  row["false_balls"] = falseBalls;
  row["falls"] = falls;
  row["sim_s"] = rounded(world.time(), 1e3);
  row["wall_s"] = rounded(std::chrono::duration<double>(Clock::now() - wallStart).count(), 1e2);
  return row;
}

namespace {

nlohmann::json quantile(std::vector<double> v, double q) {
  if (v.empty()) return nullptr;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

void append(std::vector<double>& to, const nlohmann::json& a) {
  for (const auto& x : a) to.push_back(x.get<double>());
}

// The figures of a set of rows (already in seed order).
nlohmann::json figures(const std::vector<const nlohmann::json*>& rows) {
  std::vector<double> position, heading, recovery, rollingEnd;
  std::map<std::string, std::vector<double>> ballStatic{{"0-2", {}}, {"2-4", {}}, {"4-6", {}}};
  long runs = 0, valid = 0, mirrored = 0, claims = 0, falseBalls = 0, kidnaps = 0, recovered = 0, rolls = 0, falls = 0;
  long legsGiven = 0, legsReached = 0;
  for (const nlohmann::json* r : rows) {
    append(position, r->at("position_error_m"));
    append(heading, r->at("heading_error_deg"));
    runs += r->at("runs").get<long>();
    valid += r->at("valid").get<long>();
    mirrored += r->at("mirrored").get<long>();
    claims += r->at("ball_claims").get<long>();
    falseBalls += r->at("false_balls").get<long>();
    falls += r->at("falls").get<long>();
    legsGiven += r->at("legs").at("given").get<long>();
    legsReached += r->at("legs").at("reached").get<long>();
    for (auto& [bin, v] : ballStatic) append(v, r->at("ball_static_error_m").at(bin));
    if (r->contains("kidnap")) {
      ++kidnaps;
      const auto& k = r->at("kidnap");
      if (k.at("recovered").get<bool>()) {
        ++recovered;
        recovery.push_back(k.at("recovery_s").get<double>());
      }
    }
    if (r->contains("rolling")) {
      ++rolls;
      const auto& e = r->at("rolling").at("end_error_m");
      const double roll = r->at("rolling").at("roll_m").get<double>();
      if (!e.is_null() && roll >= kRollMin && roll <= kRollMax) rollingEnd.push_back(e.get<double>());
    }
  }
  nlohmann::json staticJson;
  for (const auto& [bin, v] : ballStatic)
    staticJson[bin] = {{"median", quantile(v, 0.5)}, {"p95", quantile(v, 0.95)}, {"samples", v.size()}};
  auto fraction = [](long a, long b) { return b > 0 ? nlohmann::json(static_cast<double>(a) / static_cast<double>(b)) : nlohmann::json(); };
  return {{"trials", rows.size()},
          {"position_error_m", {{"median", quantile(position, 0.5)}, {"p95", quantile(position, 0.95)}, {"max", quantile(position, 1.0)}}},
          {"heading_error_deg", {{"median", quantile(heading, 0.5)}, {"p95", quantile(heading, 0.95)}, {"max", quantile(heading, 1.0)}}},
          {"mirrored_fraction", fraction(mirrored, valid)},
          {"valid_fraction", fraction(valid, runs)},
          {"images_scored", runs},
          {"kidnap", {{"trials", kidnaps}, {"recovered", recovered}, {"recovery_s_median", quantile(recovery, 0.5)},
                      {"recovery_s_p95", quantile(recovery, 0.95)}}},
          {"ball", {{"static_error_m", staticJson},
                    {"rolling_end_error_m", {{"median", quantile(rollingEnd, 0.5)}, {"p95", quantile(rollingEnd, 0.95)},
                                             {"trials", rolls}, {"scored", rollingEnd.size()}}},
                    {"false_ball_fraction", fraction(falseBalls, claims)},
                    {"false_balls", falseBalls},
                    {"ball_claims", claims}}},
          {"legs", {{"given", legsGiven}, {"reached", legsReached}}},
          {"falls", falls}};
}

}  // namespace

nlohmann::json aggregateLocalizationRows(std::vector<nlohmann::json> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a.at("seed").get<std::uint64_t>() < b.at("seed").get<std::uint64_t>(); });
  std::vector<const nlohmann::json*> all;
  std::map<std::string, std::vector<const nlohmann::json*>> byLighting;
  nlohmann::json seeds = nlohmann::json::array();
  for (const auto& r : rows) {
    all.push_back(&r);
    byLighting[r.at("lighting").get<std::string>()].push_back(&r);
    seeds.push_back(r.at("seed"));
  }
  nlohmann::json j = figures(all);
  nlohmann::json by = nlohmann::json::object();
  for (const auto& [name, v] : byLighting) by[name] = figures(v);
  j["by_lighting"] = by;
  j["seeds"] = seeds;
  if (!rows.empty()) j["settings"] = rows.front().at("settings");
  return j;
}

nlohmann::json evalLocalization(const LocalizationEvalOptions& o, std::vector<nlohmann::json> rows,
                                const std::function<void(const nlohmann::json& row)>& onRow) {
  const std::vector<std::uint64_t> seeds = trialSeeds(o.seed, o.trials, o.seeds, "--trials");
  if (o.lightings.empty()) throw Error("--lighting", "no lighting");
  const nlohmann::json settings = localizationEvalSettings(o);
  const auto checkLighting = [&](const nlohmann::json& row) {
    const std::uint64_t seed = row.at("seed").get<std::uint64_t>();
    const std::string lighting = lightingOf(o, seed).name;
    if (row.at("lighting") != lighting)
      throw Error("--rows", "the row of seed " + std::to_string(seed) + " has lighting " + row.at("lighting").dump() +
                                ", this run " + lighting);
  };
  return aggregateLocalizationRows(collectRows(
      seeds, rowsBySeed(std::move(rows), settings), [&](std::uint64_t seed) { return runLocalizationTrial(o, seed); },
      onRow, o.progress, checkLighting));
}

}  // namespace nao::sim
