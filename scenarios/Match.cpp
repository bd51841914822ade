#include "scenarios/Match.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <random>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/modeling/RobotPose.h"
#include "robot/Error.h"
#include "robot/nao/GameController.h"
#include "scenarios/BallRules.h"
#include "scenarios/GameControllerSim.h"
#include "scenarios/RobotRules.h"
#include "scenarios/WalkEval.h"
#include "sim/CameraRenderer.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

constexpr int kBalls = 4;
const char* kTeamNames[2] = {"home", "away"};

// The x sign of `team`'s own half.
double ownSign(int team, bool homeNegative) { return (team == 0) == homeNegative ? -1.0 : 1.0; }

// Before each half and on a penalty's return: on the side line nearest the GameController
// (y < 0), in line with the own penalty mark, facing the field.
Eigen::Vector3d startPose(const FieldDimensions& f, int team, bool homeNegative) {
  return {ownSign(team, homeNegative) * (f.length / 2 - f.penaltyCrossDistance), -f.width / 2, M_PI / 2};
}

// A removed robot stands off the carpet behind the GameController's side line.
Eigen::Vector3d parkPose(const FieldDimensions& f, int team, bool homeNegative) {
  return {ownSign(team, homeNegative) * (f.length / 2 - f.penaltyCrossDistance), -f.width / 2 - f.borderStripWidth - 1.5,
          M_PI / 2};
}

Eigen::Vector3d parkedBall(const FieldDimensions& f, int i) {
  return {-1.5 + i, f.width / 2 + f.borderStripWidth + 2.0, 0.05};
}

double tiltDeg(const Eigen::Isometry3d& torso) {
  return std::acos(std::clamp(torso.linear()(2, 2), -1.0, 1.0)) * 180 / M_PI;
}

struct Sample {
  double t;
  Eigen::Vector3d pose;
  double headYaw;
};

struct Player {
  std::unique_ptr<SimBackend> backend;
  std::unique_ptr<RobotProgram> program;
  std::unique_ptr<GameController> receiver;
  std::unique_ptr<RobotRules> rules;
  std::deque<Sample> recent;  // the last 2 s, one sample per 0.1 s
  double nextSample = 0;
  bool wasPenalised = false, wasFallen = false;
  int falls = 0, penalties = 0;
  double distance = 0;
  Eigen::Vector3d lastPose = Eigen::Vector3d::Zero();
  std::vector<double> localizationErrors;
};

}  // namespace

MatchResult runMatch(const MatchOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  const FieldDimensions& f = o.field;
  bool homeNegative = true;
  SceneSpec spec;
  spec.field = f;
  spec.robotModel = o.robotModel;
  spec.robots = {startPose(f, 0, true), startPose(f, 1, true)};
  for (int i = 0; i < kBalls; ++i) spec.balls.push_back(parkedBall(f, i));
  World world(spec, o.seed);
  nlohmann::json robotsJson = nlohmann::json::array();
  for (int r = 0; r < 2; ++r) {
    if (o.randomize) applyVariation(world, r, RobotVariation{}, o.seed * 2654435761ULL + 31 * static_cast<std::uint64_t>(r) + 7);
    world.placeRobot(r, spec.robots[static_cast<std::size_t>(r)], StandController::standPosture());
  }
  CameraRenderer renderer(world.model());
  std::mt19937_64 noise(o.seed ^ 0x6a09e667f3bcc909ULL), toss(o.seed * 0x9e3779b97f4a7c15ULL + 11);

  GameControllerSim::Config gcConfig;
  gcConfig.teams = o.teams;
  gcConfig.halfSeconds = o.halfSeconds;
  GameControllerSim gc(gcConfig);
  BallRules ballRules(f);
  nlohmann::json events = nlohmann::json::array();
  auto event = [&](nlohmann::json e) {
    e["t"] = world.time();
    events.push_back(std::move(e));
  };
  std::array<Player, 2> players;
  for (int r = 0; r < 2; ++r) {
    Player& p = players[static_cast<std::size_t>(r)];
    p.backend = std::make_unique<SimBackend>(world, r, false);
    p.backend->setImageSource([&world, &renderer, &o, &noise, r](CameraId cam, double time) {
      const CameraResolution res = world.cameraResolution(cam);
      return renderer.renderImage(world.model(), world.data(), world.cameraIndex(r, cam), res.width, res.height,
                                  o.lighting, cam, time, noise);
    });
    RobotProgramConfig config;
    config.field = f;
    p.program = std::make_unique<RobotProgram>(config);
    GameController::Config rc;
    rc.team = o.teams[static_cast<std::size_t>(r)];
    rc.player = 1;
    rc.port = 0;
    rc.bindAddress = "127.0.0.1";
    // What each robot's receiver logs (state changes, rejected packets) goes to the event log.
    p.receiver = std::make_unique<GameController>(
        rc, [&event, r](const std::string& line) { event({{"kind", "robot_log"}, {"team", kTeamNames[r]}, {"text", line}}); });
    p.rules = std::make_unique<RobotRules>(f, r);
    p.lastPose = world.robotPose(r);
  }

  std::array<std::array<int, 2>, 2> pointsByKind{};  // team -> {goal, ball_in_half}
  std::array<bool, kBalls> inPlay{};
  std::array<double, kBalls> lastSide{};  // each ball's half (sign of x), 0 on the line
  double lastCrossing = 0, stateSince = 0;
  gc::State lastState = gc.state();
  std::size_t gcEvents = 0;
  double nextProgress = 0;

  auto placeBalls = [&] {
    const auto points = ballRules.startPoints();
    for (int i = 0; i < kBalls; ++i) {
      world.placeBall(i, Eigen::Vector3d(points[static_cast<std::size_t>(i)].x(), points[static_cast<std::size_t>(i)].y(), 0.05));
      ballRules.replaced(i);
      inPlay[static_cast<std::size_t>(i)] = true;
      lastSide[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)].x() > 0 ? 1 : -1;
    }
    world.takeBallContacts();
    event({{"kind", "place"}, {"what", "balls on the goal free-kick positions"}});
  };
  auto placeAtStart = [&](int r, const char* why) {
    world.placeRobot(r, startPose(f, r, homeNegative), StandController::standPosture());
    players[static_cast<std::size_t>(r)].rules->placed();
    players[static_cast<std::size_t>(r)].lastPose = world.robotPose(r);
    event({{"kind", "place"}, {"team", kTeamNames[r]}, {"what", why}});
  };

  const double endTime = o.seconds > 0 ? o.seconds : 1e9;
  double readyAt = 2.0;  // the operator's kick-off, 2 s after the robots stand at their starts
  while (world.time() < endTime - 1e-9 && !gc.finished()) {
    world.stepCycle();
    const double t = world.time();
    for (int r = 0; r < 2; ++r) {
      Player& p = players[static_cast<std::size_t>(r)];
      p.program->blackboard().write<GameControllerData>() =
          GameControllerData{p.receiver->gameControllerActive(t), p.receiver->state()};
      if (!p.program->cycle(*p.backend))
        throw Error("match", std::string(kTeamNames[r]) + " robot stopped: " + p.backend->stopReason());
    }
    // The operator.
    if (gc.state() == gc::State::Initial && readyAt >= 0 && t >= readyAt) {
      gc.ready(t);
      readyAt = -1;
    }
    if (gc.state() == gc::State::Ready && t - stateSince >= 5) {
      bool still = true;  // both robots have stood for 2 s: in position
      for (const Player& p : players)
        if (p.recent.size() < 20 || (p.recent.back().pose - p.recent.front().pose).head<2>().norm() > 0.03) still = false;
      if (still) gc.set(t);
    }
    gc.update(t);
    if (gc.state() != lastState) {
      lastState = gc.state();
      stateSince = t;
      if (lastState == gc::State::Set) placeBalls();
      if (lastState == gc::State::Playing) lastCrossing = t;
      if (lastState == gc::State::Finished && gc.firstHalf() && !gc.finished()) {
        // Half time: the sides switch; the robots stand at their new starts, the balls are taken off.
        homeNegative = false;
        ballRules.setHomeDefendsNegativeX(false);
        for (int r = 0; r < 2; ++r) {
          players[static_cast<std::size_t>(r)].rules->setHomeDefendsNegativeX(false);
          placeAtStart(r, "second half start");
        }
        for (int i = 0; i < kBalls; ++i) {
          world.placeBall(i, parkedBall(f, i));
          inPlay[static_cast<std::size_t>(i)] = false;
        }
        gc.startSecondHalf(t);
        lastState = gc.state();
        readyAt = t + 2.0;
      }
    }
    if (gc.packetDue(t)) {
      const auto packet = gc.packet();
      for (Player& p : players) p.receiver->handlePacket(packet.data(), packet.size(), t);
    }
    for (; gcEvents < gc.events().size(); ++gcEvents) {
      const auto& e = gc.events()[gcEvents];
      nlohmann::json j = {{"kind", "gc_" + e.kind}, {"text", e.text}};
      if (e.team >= 0) j["team"] = kTeamNames[e.team];
      event(j);
    }

    // The referee's eyes: the robots.
    for (int r = 0; r < 2; ++r) {
      Player& p = players[static_cast<std::size_t>(r)];
      const Eigen::Vector3d pose = world.robotPose(r);
      p.distance += (pose - p.lastPose).head<2>().norm();
      p.lastPose = pose;
      if (t >= p.nextSample) {
        p.recent.push_back({t, pose, world.sensors(r).joints.position[HeadYaw]});
        while (!p.recent.empty() && p.recent.front().t < t - 2.0) p.recent.pop_front();
        p.nextSample = t + 0.1;
        // The belief against the truth, mapped from the robot's own frame (it attacks +x).
        const Blackboard& cognition = p.program->cognitionBoard();
        if (cognition.has<RobotPose>() && cognition.read<RobotPose>().valid && !gc.penalised(r, 1)) {
          const Pose2& b = cognition.read<RobotPose>().pose;
          const double sign = -ownSign(r, homeNegative);  // +1: own frame = field frame
          p.localizationErrors.push_back((Eigen::Vector2d(sign * b.x, sign * b.y) - pose.head<2>()).norm());
        }
      }
      const bool penalised = gc.penalised(r, 1);
      if (p.wasPenalised && !penalised) placeAtStart(r, "return after the penalty");
      p.wasPenalised = penalised;
      if (penalised) continue;
      RobotRules::Truth truth;
      const auto corners = world.soleCorners(r);
      for (int k = 0; k < 8; ++k) truth.soleCorners[static_cast<std::size_t>(k)] = corners[static_cast<std::size_t>(k)].head<2>();
      for (int foot = 0; foot < 2; ++foot) {
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        for (int k = 0; k < 4; ++k) c += truth.soleCorners[static_cast<std::size_t>(4 * foot + k)] / 4;
        truth.feet[static_cast<std::size_t>(foot)] = c;
      }
      const Eigen::Isometry3d torso = world.torsoPose(r);
      truth.torso = torso.translation().head<2>();
      truth.tilt = tiltDeg(torso);
      truth.height = torso.translation().z();
      if (p.recent.size() >= 10) {
        const Sample& a = p.recent[p.recent.size() - 10];
        const Sample& b = p.recent.back();
        truth.active = (b.pose - a.pose).head<2>().norm() > 0.05 || std::abs(Pose2::wrap(b.pose.z() - a.pose.z())) > 0.15 ||
                       std::abs(b.headYaw - a.headYaw) > 0.1;
      }
      for (int i = 0; i < kBalls; ++i)
        for (bool left : {true, false})
          if (inPlay[static_cast<std::size_t>(i)] && (world.handPosition(r, left) - world.ballPosition(i)).norm() < 0.09)
            truth.handOnBall = true;
      if (const auto call = p.rules->update(t, gc.state(), truth)) {
        event({{"kind", "call"}, {"rule", ruleName(call->rule)}, {"team", kTeamNames[r]}, {"evidence", call->evidence}});
        gc.penalise(r, 1, call->rule, t);
        ++p.penalties;
        if (gc.penalised(r, 1) && call->rule != PenaltyRule::MotionInSet) {  // removed (or excluded)
          world.placeRobot(r, parkPose(f, r, homeNegative), StandController::standPosture());
          p.rules->placed();
          p.lastPose = world.robotPose(r);
        }
        p.wasPenalised = gc.penalised(r, 1);
      }
      if (p.rules->fallen() && !p.wasFallen) {
        ++p.falls;
        event({{"kind", "fall"}, {"team", kTeamNames[r]}});
      }
      p.wasFallen = p.rules->fallen();
    }

    // The balls.
    std::vector<BallRules::Ball> balls(kBalls);
    for (int i = 0; i < kBalls; ++i) {
      balls[static_cast<std::size_t>(i)].position = world.ballPosition(i).head<2>();
      balls[static_cast<std::size_t>(i)].velocity = world.ballVelocity(i).head<2>();
      balls[static_cast<std::size_t>(i)].inPlay = inPlay[static_cast<std::size_t>(i)];
      const double x = balls[static_cast<std::size_t>(i)].position.x(), edge = f.lineWidth / 2 + 0.05;
      const double side = x > edge ? 1 : x < -edge ? -1 : 0;
      if (inPlay[static_cast<std::size_t>(i)] && side != 0 && side != lastSide[static_cast<std::size_t>(i)]) {
        lastSide[static_cast<std::size_t>(i)] = side;
        lastCrossing = t;
      }
    }
    std::vector<BallRules::Touch> touches;
    for (const World::BallContact& c : world.takeBallContacts()) {
      touches.push_back({c.ball, c.robot});
      event({{"kind", "ball_contact"}, {"team", kTeamNames[c.robot]}, {"ball", c.ball}});
    }
    const std::vector<Eigen::Vector2d> robotPositions = {world.robotPose(0).head<2>(), world.robotPose(1).head<2>()};
    for (const BallRules::Call& c : ballRules.update(t, balls, touches, robotPositions)) {
      if (c.kind == "point" && gc.state() == gc::State::Playing) {
        gc.point(c.team, t);
        ++pointsByKind[static_cast<std::size_t>(c.team)][c.how == "goal" ? 0 : 1];
        event({{"kind", "point"}, {"team", kTeamNames[c.team]}, {"how", c.how}, {"ball", c.ball}, {"at", {c.at.x(), c.at.y()}}});
      } else if (c.kind == "no_point") {
        event({{"kind", "no_point"}, {"reason", c.how}, {"team", kTeamNames[c.team]}, {"ball", c.ball}});
      } else if (c.kind != "point") {
        event({{"kind", "call"}, {"rule", c.kind}, {"ball", c.ball}, {"evidence", {{"at", {c.at.x(), c.at.y()}}}}});
      }
      if (c.replaceAt) {
        world.placeBall(c.ball, Eigen::Vector3d(c.replaceAt->x(), c.replaceAt->y(), 0.05));
        ballRules.replaced(c.ball);
        event({{"kind", "place"}, {"what", "ball"}, {"ball", c.ball}, {"at", {c.replaceAt->x(), c.replaceAt->y()}}});
      }
    }
    // Global game stuck: no ball from one half to the other for a minute.
    if (gc.state() == gc::State::Playing && t - lastCrossing >= 60) {
      event({{"kind", "call"}, {"rule", "global_game_stuck"}, {"evidence", "no ball crossed the halfway line for 60 s"}});
      gc.globalGameStuck(t);
      lastState = gc.state();
      stateSince = t;
      for (int i = 0; i < kBalls; ++i) {
        world.placeBall(i, parkedBall(f, i));
        inPlay[static_cast<std::size_t>(i)] = false;
      }
    }
    if (o.progress && t >= nextProgress) {
      o.progress(t, std::string(gc::stateName(gc.state())) + " " + std::to_string(gc.score(0)) + ":" +
                        std::to_string(gc.score(1)) + ", " + std::to_string(static_cast<int>(gc.secsRemaining())) + " s left");
      nextProgress = t + 10;
    }
  }
  if (gc.finished() && gc.winner() < 0) gc.coinToss(static_cast<int>(toss() % 2), world.time());
  for (; gcEvents < gc.events().size(); ++gcEvents) {
    const auto& e = gc.events()[gcEvents];
    events.push_back({{"t", e.t}, {"kind", "gc_" + e.kind}, {"text", e.text}});
  }

  MatchResult result;
  result.homeScore = gc.score(0);
  result.awayScore = gc.score(1);
  result.state = gc::stateName(gc.state());
  result.simSeconds = world.time();
  result.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  nlohmann::json robots = nlohmann::json::array();
  for (int r = 0; r < 2; ++r) {
    Player& p = players[static_cast<std::size_t>(r)];
    std::vector<double> e = p.localizationErrors;
    double median = -1;
    if (!e.empty()) {
      std::nth_element(e.begin(), e.begin() + static_cast<long>(e.size() / 2), e.end());
      median = e[e.size() / 2];
    }
    robots.push_back({{"team", kTeamNames[r]},
                      {"falls", p.falls},
                      {"penalties", p.penalties},
                      {"distance_m", p.distance},
                      {"localization_error_m", median}});
  }
  result.json = {{"score", {{"home", result.homeScore}, {"away", result.awayScore}}},
                 {"points_by_kind",
                  {{"home", {{"goal", pointsByKind[0][0]}, {"ball_in_half", pointsByKind[0][1]}}},
                   {"away", {{"goal", pointsByKind[1][0]}, {"ball_in_half", pointsByKind[1][1]}}}}},
                 {"winner", gc.winner() < 0 ? nlohmann::json(nullptr) : nlohmann::json(kTeamNames[gc.winner()])},
                 {"events", events},
                 {"robots", robots},
                 {"sim_s", result.simSeconds},
                 {"wall_s", result.wallSeconds},
                 {"rtf", result.wallSeconds > 0 ? result.simSeconds / result.wallSeconds : 0.0},
                 {"state", result.state},
                 {"seed", o.seed}};
  return result;
}

}  // namespace nao::sim
