#include "scenarios/Match.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <random>
#include <thread>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/perception/FallState.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"
#include "robot/Error.h"
#include "robot/nao/GameController.h"
#include "scenarios/BallRules.h"
#include "scenarios/GameControllerLink.h"
#include "scenarios/GameControllerSim.h"
#include "scenarios/MatchReplay.h"
#include "scenarios/RobotRules.h"
#include "scenarios/WalkEval.h"
#include "robot/OutputFiles.h"
#include "sim/CameraRenderer.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"
#include "sim/OracleCamera.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

// Adds its scope's wall time to `total` (seconds): where a match's time goes (bench match).
class Stopwatch {
 public:
  explicit Stopwatch(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

constexpr int kBalls = 4;
const char* kTeamNames[2] = {"home", "away"};

// The x sign of `team`'s own half.
// A robot's beliefs (its RobotPose and BallModel), from its own frame, where it attacks +x, to
// the field's: `sign` is -1 where the two differ.
EstimateOverlay beliefInField(const Blackboard& cognition, double sign) {
  EstimateOverlay belief;
  if (cognition.has<RobotPose>() && cognition.read<RobotPose>().valid) {
    const RobotPose& b = cognition.read<RobotPose>();
    belief.pose = Eigen::Vector3d(sign * b.pose.x, sign * b.pose.y, Pose2::wrap(b.pose.theta + (sign < 0 ? M_PI : 0.0)));
    belief.positionCovariance = b.covariance.topLeftCorner<2, 2>();
  }
  if (cognition.has<BallModel>() && cognition.read<BallModel>().fieldValid)
    belief.ball = sign * cognition.read<BallModel>().fieldPosition;
  return belief;
}

// Jerseys in the GameController protocol's field player colours (codes 0..9: blue, red, yellow,
// black, white, green, orange, purple, brown, grey), worn on the torso.
const char* const kColourNames[10] = {"blue", "red", "yellow", "black", "white", "green", "orange", "purple", "brown", "grey"};
Eigen::Vector4d jerseyColour(int code) {
  static const double rgb[10][3] = {{0.10, 0.25, 0.85}, {0.85, 0.10, 0.10}, {0.95, 0.85, 0.10}, {0.08, 0.08, 0.08},
                                    {0.97, 0.97, 0.97}, {0.10, 0.60, 0.15}, {0.98, 0.50, 0.05}, {0.50, 0.15, 0.65},
                                    {0.45, 0.28, 0.12}, {0.50, 0.50, 0.50}};
  const int c = code >= 0 && code < 10 ? code : 9;
  return {rgb[c][0], rgb[c][1], rgb[c][2], 1.0};
}

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
  bool present = true;    // false: parked off the carpet for a situation, not judged
  bool scripted = false;  // driven by a situation's script
  std::size_t step = 0;   // the script's next step
  MotionRequest request;  // the script's current request
  int walkId = 0;
  std::unique_ptr<SimBackend> backend;
  std::unique_ptr<RobotProgram> program;
  std::unique_ptr<GameController> receiver;
  std::map<std::string, double> lastAdvice;  // --gc udp: when each rule was last called for this robot
  std::unique_ptr<RobotRules> rules;
  std::deque<Sample> recent;  // the last 2 s, one sample per 0.1 s
  double nextSample = 0;
  bool wasPenalised = false, wasFallen = false;
  int falls = 0, penalties = 0;
  double distance = 0;
  Eigen::Vector3d lastPose = Eigen::Vector3d::Zero();
  std::vector<double> localizationErrors;
};

// Poses and balls of a situation must lie on the carpet (the field and its border strip).
void checkSituation(const Situation& s, const FieldDimensions& f) {
  auto onCarpet = [&f](const Eigen::Vector2d& p) {
    return std::abs(p.x()) <= f.length / 2 + f.borderStripWidth && std::abs(p.y()) <= f.width / 2 + f.borderStripWidth;
  };
  for (int r = 0; r < 2; ++r) {
    const SituationRobot& sr = s.robots[static_cast<std::size_t>(r)];
    if (!sr.present) continue;
    if (!onCarpet(sr.pose.head<2>())) throw Error("situation", std::string(kTeamNames[r]) + " robot: its pose is off the carpet");
    for (const SituationStep& step : sr.script)
      if (step.action == "walk_to" && !onCarpet(step.pose.head<2>()) &&
          std::abs(step.pose.x()) > f.length / 2 + f.borderStripWidth + 1.0)
        throw Error("situation", std::string(kTeamNames[r]) + " robot: walk_to more than 1 m beyond the carpet");
  }
  for (std::size_t i = 0; i < s.balls.size(); ++i)
    if (!onCarpet(s.balls[i].position)) throw Error("situation", "balls[" + std::to_string(i) + "]: off the carpet");
}

// Whether a ball in play lies in the view of one of robot r's cameras: the rules count looking
// at a ball as activity (a robot waiting for the ball, facing it, is not inactive).
bool looksAtABall(const World& world, int r, const std::array<bool, kBalls>& inPlay) {
  const double halfY = world.cameraFovY() / 2;
  for (const CameraId camera : {CameraId::Top, CameraId::Bottom}) {
    const CameraResolution size = world.cameraResolution(camera);
    const double halfX = std::atan(std::tan(halfY) * size.width / size.height);
    const Eigen::Isometry3d toCamera = world.cameraPose(r, camera).inverse();
    for (int i = 0; i < kBalls; ++i) {
      if (!inPlay[static_cast<std::size_t>(i)]) continue;
      const Eigen::Vector3d b = toCamera * world.ballPosition(i);
      if (b.x() > 0.05 && std::abs(std::atan2(b.y(), b.x())) < halfX && std::abs(std::atan2(b.z(), b.x())) < halfY)
        return true;
    }
  }
  return false;
}

// A scripted robot's steps due at this cycle: its motion request, the push of a fall, a kick's
// ball (the nearest ball in play within 0.35 m of the robot, given the step's velocity and
// counted as this robot's touch).
template <class Event>
void runScript(World& world, int r, const SituationRobot& sr, Player& p, const std::array<bool, kBalls>& inPlay,
               std::vector<BallRules::Touch>& touches, Event& event) {
  const double t = world.time();
  while (p.step < sr.script.size() && sr.script[p.step].t <= t + 1e-9) {
    const SituationStep& step = sr.script[p.step++];
    event({{"kind", "script"}, {"team", kTeamNames[r]}, {"what", step.action}});
    const Eigen::Vector3d now = world.robotPose(r);
    MotionRequest m;  // stand
    if (step.action == "walk_to") {
      m.motion = MotionType::WalkTo;
      m.walkTarget = Pose2(now.x(), now.y(), now.z()).inverse() * Pose2(step.pose.x(), step.pose.y(), step.pose.z());
      m.walkTargetId = ++p.walkId;
    } else if (step.action == "sit") {
      m.motion = MotionType::SitDown;
    } else if (step.action == "fall") {
      // Tipped over forwards (7 N s at the torso; the stand withstands 4) and left lying until
      // the next step says lie or get up.
      world.pushRobot(r, 7.0 * Eigen::Vector3d(std::cos(now.z()), std::sin(now.z()), 0));
      m.motion = MotionType::PlayDead;
    } else if (step.action == "lie") {
      m.motion = MotionType::PlayDead;
    } else if (step.action == "get_up") {
      m.motion = MotionType::GetUp;
    } else if (step.action == "kick") {
      int nearest = -1;
      double best = 0.35;
      for (int i = 0; i < kBalls; ++i) {
        const double d = (world.ballPosition(i).head<2>() - now.head<2>()).norm();
        if (inPlay[static_cast<std::size_t>(i)] && d < best) {
          best = d;
          nearest = i;
        }
      }
      if (nearest >= 0) {
        const double a = step.directionDeg * M_PI / 180;
        const Eigen::Vector3d at = world.ballPosition(nearest);
        world.placeBall(nearest, Eigen::Vector3d(at.x(), at.y(), 0.05), step.speed * Eigen::Vector3d(std::cos(a), std::sin(a), 0));
        touches.push_back({nearest, r});
      }
    }
    p.request = m;
  }
}

}  // namespace

MatchResult runMatch(const MatchOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  const FieldDimensions& f = o.field;
  const Situation* situation = o.situation ? &*o.situation : nullptr;
  bool homeNegative = situation ? situation->firstHalf : true;
  SceneSpec spec;
  spec.field = f;
  spec.robotModel = o.robotModel;
  spec.venue = o.venue;
  spec.venueSeed = o.seed;
  spec.robots = {startPose(f, 0, true), startPose(f, 1, true)};
  if (situation) checkSituation(*situation, f);
  for (int r = 0; situation && r < 2; ++r) {
    const SituationRobot& sr = situation->robots[static_cast<std::size_t>(r)];
    spec.robots[static_cast<std::size_t>(r)] = sr.present ? sr.pose : parkPose(f, r, homeNegative);
  }
  for (int i = 0; i < kBalls; ++i) spec.balls.push_back(parkedBall(f, i));
  World world(spec, o.seed);
  nlohmann::json robotsJson = nlohmann::json::array();
  for (int r = 0; r < 2; ++r) {
    if (o.randomize) applyVariation(world, r, RobotVariation{}, o.seed * 2654435761ULL + 31 * static_cast<std::uint64_t>(r) + 7);
    world.placeRobot(r, spec.robots[static_cast<std::size_t>(r)], StandController::standPosture());
  }
  const bool oracle = o.percepts == "oracle";
  if (!oracle && o.percepts != "vision") throw Error("--percepts", "'" + o.percepts + "' is neither vision nor oracle");
  std::optional<CameraRenderer> renderer;  // the fast percept mode renders nothing
  if (!oracle) renderer.emplace(world.model());
  std::mt19937_64 noise(o.seed ^ 0x6a09e667f3bcc909ULL), toss(o.seed * 0x9e3779b97f4a7c15ULL + 11);

  GameControllerSim::Config gcConfig;
  gcConfig.teams = o.teams;
  gcConfig.halfSeconds = o.halfSeconds;
  GameControllerSim gc(gcConfig);
  const bool external = o.gc == "udp";
  if (external && o.situation) throw Error("--gc", "udp runs a game, not a scripted situation");
  std::optional<GameControllerLink> link;
  if (external) link.emplace(o.gcPort);
  for (int r = 0; r < 2; ++r) world.setGeomColour(r, "torso_geom", jerseyColour(gcConfig.colours[static_cast<std::size_t>(r)]));
  BallRules ballRules(f);
  nlohmann::json events = nlohmann::json::array();
  const bool pictures = !o.imagesDir.empty();
  std::vector<std::string> picturesDue;  // --images: pictures to take at the end of the step
  std::function<void(const std::string&)> takePictures;  // set once the robots exist
  auto event = [&](nlohmann::json e) {
    e["t"] = world.time();
    if (pictures && (e["kind"] == "point" || e["kind"] == "call")) {
      char name[32];
      std::snprintf(name, sizeof name, "event_%03zu_", static_cast<std::size_t>(events.size()));  // its index in the log
      const std::string detail = e["kind"] == "point" ? e["team"].get<std::string>() : e["rule"].get<std::string>();
      // At once, before the referee moves the ball or a robot in reply.
      const std::string picture = std::string(name) + e["kind"].get<std::string>() + "_" + detail;
      if (takePictures) takePictures(picture);
      else picturesDue.push_back(picture);
    }
    events.push_back(std::move(e));
  };
  MatchWallTime wall;
  std::array<std::array<CameraImage, 2>, 2> lastImages;  // each robot's last top and bottom image (--images)
  std::array<Player, 2> players;
  for (int r = 0; r < 2; ++r) {
    Player& p = players[static_cast<std::size_t>(r)];
    p.backend = std::make_unique<SimBackend>(world, r, false);
    const SituationRobot* sr = situation ? &situation->robots[static_cast<std::size_t>(r)] : nullptr;
    p.present = !sr || sr->present;
    p.scripted = sr && !sr->program;  // a prop of the referee's: its motion from the script, no cameras
    if (!p.scripted && oracle)
      p.backend->setImageSource([&world, &wall, r](CameraId cam, double, const ExposureWeights&) {
        const Stopwatch watch(wall.images);
        return oracleImage(world, r, cam);
      });
    else if (!p.scripted)
      p.backend->setImageSource([&world, &renderer, &o, &noise, &wall, &lastImages, pictures, r](CameraId cam, double time,
                                                                                                 const ExposureWeights& metering) {
        const Stopwatch watch(wall.images);
        const CameraResolution res = world.cameraResolution(cam);
        CameraImage image = renderer->renderImage(world.model(), world.data(), world.cameraIndex(r, cam), res.width,
                                                  res.height, o.lighting, cam, time, noise, metering);
        if (pictures) lastImages[static_cast<std::size_t>(r)][cam == CameraId::Top ? 0 : 1] = image;
        return image;
      });
    RobotProgramConfig config;
    config.field = f;
    if (p.scripted) config.withoutBehavior();
    if (r == 1 && o.opponent == "baseline") {
      config.behavior = loadParams<modules::BehaviorControl::Params>("BehaviorControl", config.configDir);
      config.behavior->striker.player = "baseline";
    } else if (r == 1 && o.opponent != "self") {
      config.configDir = o.opponent;
    }
    if (oracle) config.providers["CameraPercepts"] = "OracleVision";
    config.seed = o.seed * 2 + static_cast<std::uint64_t>(r);
    if (r == 0) config.debug = o.debug;
    p.program = std::make_unique<RobotProgram>(config);
    GameController::Config rc;
    rc.team = o.teams[static_cast<std::size_t>(r)];
    rc.player = 1;
    rc.port = 0;
    rc.bindAddress = external ? "0.0.0.0" : "127.0.0.1";
    rc.returnPort = o.gcReturnPort;
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
  // Substantial change (global game stuck's 30 s rule): a ball touched, or one moved 0.5 m from
  // where it lay at the last change.
  double lastChange = 0;
  std::array<Eigen::Vector2d, kBalls> changeAnchor{};
  bool anchored = false;
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

  double endTime = o.seconds > 0 ? o.seconds : 1e9;
  double readyAt = external ? -1.0 : 2.0;  // the operator's kick-off, 2 s after the robots stand at their starts
  std::vector<bool> kicked;  // a situation's ball velocities given
  if (situation) {
    readyAt = -1;
    endTime = situation->seconds;
    ballRules.setHomeDefendsNegativeX(homeNegative);
    for (Player& p : players) p.rules->setHomeDefendsNegativeX(homeNegative);
    gc.startAt(situation->state, situation->secsRemaining, situation->firstHalf, world.time());
    lastState = gc.state();
    for (std::size_t i = 0; i < situation->balls.size(); ++i) {
      const Eigen::Vector2d& at = situation->balls[i].position;
      world.placeBall(static_cast<int>(i), Eigen::Vector3d(at.x(), at.y(), 0.05));
      ballRules.replaced(static_cast<int>(i));
      inPlay[i] = true;
      lastSide[i] = at.x() > 0 ? 1 : -1;
    }
    kicked.assign(situation->balls.size(), false);
  }
  double playingSeconds = 0, previous = world.time(), nextFrame = 0;
  std::vector<ReplayFrame> frames;
  // --images: the field from above with the truth and both robots' beliefs (mapped from each
  // robot's own frame, where it attacks +x), and the robots' last camera images.
  nlohmann::json picturesWritten = nlohmann::json::array();
  double nextPicture = 10;
  if (pictures) io::makeDirectories(o.imagesDir);
  takePictures = [&](const std::string& name) {
    std::vector<Eigen::Vector3d> balls;
    for (int i = 0; i < kBalls; ++i) balls.push_back(world.ballPosition(i));
    cv::Mat view = drawFieldView(world.field(), {world.robotPose(0), world.robotPose(1)}, balls);
    for (int r = 0; r < 2; ++r)
      drawEstimates(view, world.field(),
                    beliefInField(players[static_cast<std::size_t>(r)].program->cognitionBoard(), -ownSign(r, homeNegative)));
    auto write = [&](const std::string& file, auto&& image) {
      writePng(o.imagesDir + "/" + file, image);
      picturesWritten.push_back(file);
    };
    write(name + "_field.png", view);
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c)
        if (lastImages[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)].valid())
          write(name + "_" + kTeamNames[r] + (c == 0 ? "_top.png" : "_bottom.png"),
                lastImages[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)]);
  };
  bool coinTossed = false;
  const auto loopStart = std::chrono::steady_clock::now();
  auto lastPacketWall = loopStart;
  const double simStart = world.time();
  const double setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  while (world.time() < endTime - 1e-9 && !gc.finished()) {
    {
      const Stopwatch watch(wall.physics);
      world.stepCycle();
    }
    const double t = world.time();
    if (gc.state() == gc::State::Playing) playingSeconds += t - previous;
    previous = t;
    std::vector<BallRules::Touch> scriptTouches;
    if (situation) {
      for (std::size_t i = 0; i < situation->balls.size(); ++i) {
        const SituationBall& b = situation->balls[i];
        if (kicked[i] || !b.velocity || t < b.at - 1e-9) continue;
        kicked[i] = true;
        const Eigen::Vector3d at = world.ballPosition(static_cast<int>(i));
        world.placeBall(static_cast<int>(i), Eigen::Vector3d(at.x(), at.y(), 0.05), Eigen::Vector3d(b.velocity->x(), b.velocity->y(), 0));
        if (b.by >= 0) scriptTouches.push_back({static_cast<int>(i), b.by});
        event({{"kind", "script"}, {"what", "ball kicked"}, {"ball", i}, {"velocity", {b.velocity->x(), b.velocity->y()}}});
      }
      for (int r = 0; r < 2; ++r)
        if (players[static_cast<std::size_t>(r)].scripted)
          runScript(world, r, situation->robots[static_cast<std::size_t>(r)], players[static_cast<std::size_t>(r)], inPlay,
                    scriptTouches, event);
    }
    for (int r = 0; r < 2; ++r) {
      Player& p = players[static_cast<std::size_t>(r)];
      p.program->blackboard().write<GameControllerData>() =
          GameControllerData{p.receiver->gameControllerActive(t), p.receiver->state()};
      if (p.scripted) p.program->blackboard().write<MotionRequest>() = p.request;
      if (!p.program->cycle(*p.backend))
        throw Error("match", std::string(kTeamNames[r]) + " robot stopped: " + p.backend->stopReason());
      const RobotProgram::CycleTiming& timing = p.program->lastTiming();
      wall.motion += timing.motionMs / 1000;
      for (double ms : timing.cognitionMs) wall.cognition += ms / 1000;
    }
    if (external) {
      // The external GameController: its datagrams to both robots, its state to the match.
      link->receive([&](const std::uint8_t* data, std::size_t size, const sockaddr_in& from) {
        for (Player& p : players) p.receiver->handlePacket(data, size, t, &from);
        try {
          if (gc.follow(gc::parseGameControlData(data, size), t)) lastPacketWall = std::chrono::steady_clock::now();
        } catch (const Error& e) {
          event({{"kind", "gc_rejected"}, {"text", e.what()}});
        }
      });
      const double silent = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastPacketWall).count();
      if (silent > o.gcWait)
        throw RunFailure("--gc", "no GameController packet for this game's teams on UDP port " + std::to_string(link->port()) +
                                " for " + std::to_string(static_cast<int>(o.gcWait)) + " s");
      // An external GameController keeps the wall clock: the simulation keeps pace with it.
      const double ahead = (t - simStart) - std::chrono::duration<double>(std::chrono::steady_clock::now() - loopStart).count();
      if (ahead > 0) std::this_thread::sleep_for(std::chrono::duration<double>(ahead));
      // Return packets (in process the receivers have no sender to answer).
      for (Player& p : players) {
        gc::ReturnData ret;
        ret.playerNum = 1;
        ret.teamNum = static_cast<std::uint8_t>(o.teams[static_cast<std::size_t>(&p - players.data())]);
        ret.fallen = p.program->blackboard().has<FallState>() && p.program->blackboard().read<FallState>().fallen ? 1 : 0;
        p.receiver->sendReturnIfDue(t, ret);
      }
    }
    // The operator.
    if (gc.state() == gc::State::Initial && readyAt >= 0 && t >= readyAt) {
      gc.ready(t);
      readyAt = -1;
    }
    if (!external && gc.state() == gc::State::Ready && t - stateSince >= 5) {
      bool still = true;  // both robots have stood for 2 s: in position
      for (const Player& p : players)
        if (p.recent.size() < 20 || (p.recent.back().pose - p.recent.front().pose).head<2>().norm() > 0.03) still = false;
      if (still) gc.set(t);
    }
    gc.update(t);
    if (gc.state() != lastState) {
      lastState = gc.state();
      stateSince = t;
      if (lastState == gc::State::Set && !situation) placeBalls();
      if (lastState == gc::State::Playing) lastCrossing = lastChange = t, anchored = false;
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
        if (!external) {
          gc.startSecondHalf(t);
          lastState = gc.state();
          readyAt = t + 2.0;
        }
      }
    }
    if (!external && gc.packetDue(t)) {
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
      if (!p.present) continue;
      const bool penalised = gc.penalised(r, 1);
      if (p.wasPenalised && !penalised) placeAtStart(r, "return after the penalty");
      if (external && !p.wasPenalised && penalised && gc.state() != gc::State::Set) {
        // Penalised by the external operator: removed, as the referee would take it off.
        world.placeRobot(r, parkPose(f, r, homeNegative), StandController::standPosture());
        p.rules->placed();
        p.lastPose = world.robotPose(r);
        event({{"kind", "place"}, {"team", kTeamNames[r]}, {"what", "removed: penalised by the GameController"}});
        ++p.penalties;
      }
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
                       std::abs(b.headYaw - a.headYaw) > 0.1 || looksAtABall(world, r, inPlay);
      }
      for (int i = 0; i < kBalls; ++i)
        for (bool left : {true, false})
          if (inPlay[static_cast<std::size_t>(i)] && (world.handPosition(r, left) - world.ballPosition(i)).norm() < 0.09)
            truth.handOnBall = true;
      if (const auto call = p.rules->update(t, gc.state(), truth)) {
        nlohmann::json callEvent = {{"kind", "call"}, {"rule", ruleName(call->rule)}, {"team", kTeamNames[r]}, {"evidence", call->evidence}};
        // With an external operator the call is advice: logged once per rule and 10 s while
        // the robot stays where the rule sees it.
        double& last = p.lastAdvice[ruleName(call->rule)];
        if (external) callEvent["applied"] = false;
        if (!external || last == 0 || t - last >= 10) event(callEvent);
        if (external) last = t;
        if (!external) {
          gc.penalise(r, 1, call->rule, t);
          ++p.penalties;
        }
        if (gc.penalised(r, 1) && call->rule != PenaltyRule::MotionInSet) {  // removed (or excluded)
          world.placeRobot(r, parkPose(f, r, homeNegative), StandController::standPosture());
          p.rules->placed();
          p.lastPose = world.robotPose(r);
        }
        p.wasPenalised = gc.penalised(r, 1);
      }
      if (p.rules->fallen() && !p.wasFallen) {
        ++p.falls;
        // Where (field frame) and how near the other robot was: a collision or the robot's own.
        nlohmann::json fall = {{"kind", "fall"}, {"team", kTeamNames[r]}, {"at", {truth.torso.x(), truth.torso.y()}}};
        if (world.robotCount() > 1) fall["other_robot_m"] = (truth.torso.head<2>() - world.robotPose(1 - r).head<2>()).norm();
        event(fall);
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
    std::vector<BallRules::Touch> touches = scriptTouches;
    for (const World::BallContact& c : world.takeBallContacts()) {
      touches.push_back({c.ball, c.robot});
      event({{"kind", "ball_contact"}, {"team", kTeamNames[c.robot]}, {"ball", c.ball}});
    }
    const std::vector<Eigen::Vector2d> robotPositions = {world.robotPose(0).head<2>(), world.robotPose(1).head<2>()};
    for (const BallRules::Call& c : ballRules.update(t, balls, touches, robotPositions)) {
      if (c.kind == "point" && gc.state() == gc::State::Playing) {
        if (!external) gc.point(c.team, t);  // else the external operator scores
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
    // Global game stuck: no substantial change for 30 s (no ball touched or moved 0.5 m), or no
    // ball from one half to the other for a minute.
    bool changed = !touches.empty() || !anchored;
    for (int i = 0; i < kBalls && !changed; ++i)
      changed = inPlay[static_cast<std::size_t>(i)] &&
                (world.ballPosition(i).head<2>() - changeAnchor[static_cast<std::size_t>(i)]).norm() >= 0.5;
    if (changed) {
      lastChange = t;
      anchored = true;
      for (int i = 0; i < kBalls; ++i) changeAnchor[static_cast<std::size_t>(i)] = world.ballPosition(i).head<2>();
    }
    const char* stuck = gc.state() != gc::State::Playing ? nullptr
                        : t - lastChange >= 30         ? "no substantial change for 30 s: no ball touched or moved 0.5 m"
                        : t - lastCrossing >= 60       ? "no ball crossed the halfway line for 60 s"
                                                       : nullptr;
    if (stuck) {
      event({{"kind", "call"}, {"rule", "global_game_stuck"}, {"evidence", stuck}});
      if (external) {
        lastChange = lastCrossing = t;  // the operator decides; judged again from now
      } else {
        gc.globalGameStuck(t);
        lastState = gc.state();
        stateSince = t;
        for (int i = 0; i < kBalls; ++i) {
          world.placeBall(i, parkedBall(f, i));
          inPlay[static_cast<std::size_t>(i)] = false;
        }
      }
    }
    if (o.replay && t >= nextFrame - 1e-9) {
      while (nextFrame <= t + 1e-9) nextFrame += 0.1;  // ten frames a simulated second, on a fixed grid
      ReplayFrame fr;
      fr.t = t;
      fr.state = gc::stateName(gc.state());
      fr.score = {gc.score(0), gc.score(1)};
      for (int r = 0; r < 2; ++r) {
        ReplayFrame::Robot& rf = fr.robots[static_cast<std::size_t>(r)];
        rf.pose = world.robotPose(r);
        rf.penalised = gc.penalised(r, 1);
        const EstimateOverlay belief =
            beliefInField(players[static_cast<std::size_t>(r)].program->cognitionBoard(), -ownSign(r, homeNegative));
        rf.beliefValid = belief.pose.has_value();
        if (belief.pose) rf.belief = *belief.pose;
        rf.ballValid = belief.ball.has_value();
        if (belief.ball) rf.ball = *belief.ball;
      }
      for (int i = 0; i < kBalls; ++i) fr.balls.push_back(world.ballPosition(i).head<2>());
      frames.push_back(std::move(fr));
    }
    if (o.progress && t >= nextProgress) {
      o.progress(t, std::string(gc::stateName(gc.state())) + " " + std::to_string(gc.score(0)) + ":" +
                        std::to_string(gc.score(1)) + ", " + std::to_string(static_cast<int>(gc.secsRemaining())) + " s left");
      nextProgress = t + 10;
    }
    if (pictures) {
      if (t >= nextPicture - 1e-9) {
        char name[32];
        std::snprintf(name, sizeof name, "t%04.0f", nextPicture);
        picturesDue.push_back(name);
        nextPicture += 10;
      }
      for (const std::string& name : picturesDue) takePictures(name);
      picturesDue.clear();
    }
  }
  if (pictures) takePictures("final");
  if (gc.finished() && gc.winner() < 0) {
    gc.coinToss(static_cast<int>(toss() % 2), world.time());
    coinTossed = true;
  }
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
  result.wall = wall;
  result.wall.setup = setupSeconds;
  if (renderer) {
    result.glVendor = renderer->glVendor();
    result.glRenderer = renderer->glRenderer();
    result.glPlatform = renderer->glPlatform();
  }
  nlohmann::json robots = nlohmann::json::array();
  for (int r = 0; r < 2; ++r) {
    Player& p = players[static_cast<std::size_t>(r)];
    std::vector<double> e = p.localizationErrors;
    double median = -1;
    if (!e.empty()) {
      std::nth_element(e.begin(), e.begin() + static_cast<long>(e.size() / 2), e.end());
      median = e[e.size() / 2];
    }
    const int colour = gcConfig.colours[static_cast<std::size_t>(r)];
    robots.push_back({{"team", kTeamNames[r]},
                      {"jersey", kColourNames[colour >= 0 && colour < 10 ? colour : 9]},
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
                 {"coin_toss", coinTossed},
                 {"playing_s", playingSeconds},
                 {"sim_s", result.simSeconds},
                 {"wall_s", result.wallSeconds},
                 {"rtf", result.wallSeconds > 0 ? result.simSeconds / result.wallSeconds : 0.0},
                 {"state", result.state},
                 {"opponent", o.opponent},
                 {"percepts", o.percepts},
                 {"seed", o.seed}};
  if (pictures) result.json["images"] = picturesWritten;
  if (o.replay) result.replay = replayData(f, frames, events);
  return result;
}

}  // namespace nao::sim
