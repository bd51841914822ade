#include "scenarios/ChallengeSession.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "controllers/StandController.h"
#include "perception/calibration/CalibrationViews.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/modeling/RobotPose.h"
#include "robot/Error.h"
#include "scenarios/Calibrate.h"
#include "scenarios/WalkEval.h"
#include "sim/CameraRenderer.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {

ChallengeSession::ChallengeSession(const ChallengeSetup& setup) : setup_(setup), noiseRng_(setup.seed ^ 0x5deece66dULL) {
  const Eigen::Vector3d start = calibration::initialPosition(setup.field, setup.side);
  SceneSpec spec;
  spec.field = setup.field;
  spec.robotModel = setup.robotModel;
  spec.venue = setup.venue;
  spec.venueSeed = setup.seed;
  spec.robots = {start};
  spec.balls = {Eigen::Vector3d(-setup.field.length / 4, 0, 0.05), Eigen::Vector3d(setup.field.length / 4, 0, 0.05)};
  world_ = std::make_unique<World>(spec, setup.seed);
  world_->setMiscalibration(0, setup.miscalibration);
  robot_ = {{"randomized", setup.randomize}};
  if (setup.randomize) {
    // A foreign robot. The head's two joint offsets stay zero: a pitch offset is a camera pitch
    // offset to the calibration (it would be scored as a calibration error), a yaw offset an
    // uncalibratable heading error.
    AppliedVariation v = applyVariation(*world_, 0, RobotVariation{}, setup.seed * 2654435761ULL + 17);
    v.jointOffsets[HeadYaw] = v.jointOffsets[HeadPitch] = 0;
    world_->setJointOffsets(0, v.jointOffsets);
    double maxOffset = 0;
    for (double a : v.jointOffsets) maxOffset = std::max(maxOffset, std::abs(a));
    robot_["mass_kg"] = v.totalMass;
    robot_["floor_friction"] = v.friction;
    robot_["max_joint_offset_deg"] = maxOffset * 180 / M_PI;
  }
  if (setup.floorFriction) {
    world_->setFloorFriction(*setup.floorFriction);
    robot_["floor_friction"] = *setup.floorFriction;
  }
  world_->placeRobot(0, start, StandController::standPosture());
  backend_ = std::make_unique<SimBackend>(*world_, 0, true);
  headId_ = backend_->robotInfo().headId;
  renderer_ = std::make_unique<CameraRenderer>(world_->model());
  backend_->setImageSource([this](CameraId cam, double time, const ExposureWeights& metering) {
    if (shield_) return shieldFrame(*world_, cam, time);
    const CameraResolution res = world_->cameraResolution(cam);
    return renderer_->renderImage(world_->model(), world_->data(), world_->cameraIndex(0, cam), res.width, res.height,
                                  setup_.lighting, cam, time, noiseRng_, metering);
  });
  // The robot program as on a robot that has never been calibrated: no stored offsets.
  RobotProgramConfig config;
  config.field = setup.field;
  config.calibrator = setup.calibrator;
  config.debug = setup.debug;
  program_ = std::make_unique<RobotProgram>(config);
  program_->setCognitionObserver([this](const CameraImage& image, const Blackboard& cognition) {
    for (const auto& o : observers_) o(image, cognition);
  });
  lastSpeech_ = program_->blackboard().read<SpeechRequest>().id;
}

ChallengeSession::~ChallengeSession() = default;

double ChallengeSession::time() const { return world_->time(); }

void ChallengeSession::note(const std::string& kind, const std::string& text) { events_.push_back({time(), kind, text}); }

void ChallengeSession::placeRobot() {
  world_->placeRobot(0, calibration::initialPosition(setup_.field, setup_.side), StandController::standPosture());
  referee_.placed();
  note("place", setup_.side > 0 ? "robot at the left start" : "robot at the right start");
}

void ChallengeSession::placeBalls(const std::array<Eigen::Vector2d, 2>& balls) {
  for (int i = 0; i < 2; ++i) {
    world_->placeBall(i, Eigen::Vector3d(balls[i].x(), balls[i].y(), 0.05));
    char text[64];
    std::snprintf(text, sizeof text, "ball %d at (%.3f, %.3f)", i, balls[i].x(), balls[i].y());
    note("place", text);
  }
  world_->takeBallContacts();  // a ball put down beside a foot is the referee's doing
}

void ChallengeSession::setShield(bool on) {
  shield_ = on;
  note("shield", on ? "on" : "off");
}

void ChallengeSession::cycle() {
  const Eigen::Vector3d before = world_->robotPose(0);
  if (!program_->cycle(*backend_)) throw Error("calibration challenge", "the simulated robot stopped: " + backend_->stopReason());
  const Eigen::Vector3d after = world_->robotPose(0);
  const double step = (after.head<2>() - before.head<2>()).norm();
  maxStep_ = std::max(maxStep_, step);
  pathLength_ += step;
  referee_.check(*world_, 0, events_);

  // What the robot says, and whether its arm is up then (standing, a hand above the head, in
  // truth).
  const bool armUp = referee_.armRaised(*world_, 0);
  if (armUp != armWasUp_) note("arm", armUp ? "up" : "down");
  armWasUp_ = armUp;
  const SpeechRequest& speech = program_->blackboard().read<SpeechRequest>();
  if (speech.id != lastSpeech_) {
    lastSpeech_ = speech.id;
    note("speech", speech.text);
    if (armUp) pendingReport_ = ChallengeReport{time(), speech.text};
  }
  if (time() >= nextTrack_) {
    const Blackboard& cognition = program_->cognitionBoard();
    Track t{time(), after, Eigen::Vector3d::Zero(), false};
    if (cognition.has<RobotPose>()) {
      const RobotPose& pose = cognition.read<RobotPose>();
      t.belief = Eigen::Vector3d(pose.pose.x, pose.pose.y, pose.pose.theta);
      t.beliefValid = pose.valid;
    }
    track_.push_back(t);
    nextTrack_ = std::floor(time() * 10 + 1e-9) / 10 + 0.1;
  }
  if (progress && time() >= nextProgress_) {
    progress(time());
    nextProgress_ = std::floor(time()) + 1;
  }
}

void ChallengeSession::keepLastViews() {
  addCognitionObserver([views = lastViews_](const CameraImage& image, const Blackboard& cognition) {
    if (!cognition.has<CameraPercepts>()) return;
    (*views)[static_cast<int>(image.camera)] = View{image, cognition.read<CameraPercepts>()};
  });
}

void ChallengeSession::runFor(double seconds) {
  const double end = time() + seconds;
  while (time() < end - 1e-9 && terminated().empty()) cycle();
}

double ChallengeSession::startMode(bool evaluation) {
  const Touch head = evaluation ? HeadRear : HeadFront;
  world_->setTouch(0, ChestButton, 1.0);
  world_->setTouch(0, head, 1.0);
  const double holdStart = time();
  note("button", evaluation ? "chest + head rear" : "chest + head front");
  runFor(1.2);
  world_->setTouch(0, ChestButton, 0.0);
  world_->setTouch(0, head, 0.0);
  return holdStart + 1.0;
}

void ChallengeSession::tap() {
  world_->setTouch(0, HeadMiddle, 1.0);
  note("tap", "head middle");
  runFor(0.2);
  world_->setTouch(0, HeadMiddle, 0.0);
}

std::optional<ChallengeReport> ChallengeSession::untilReport(double deadline) {
  pendingReport_.reset();
  while (time() < deadline && terminated().empty()) {
    cycle();
    if (pendingReport_) return pendingReport_;
  }
  return std::nullopt;
}

}  // namespace nao::sim
