#include "controllers/modules/BehaviorControl.h"

#include "controllers/StandController.h"
#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {
NAO_DEBUG_CHANNEL(kBehavior, "behavior", "per image: the options' states, the motion request and where the head looks");

const char* goToStateName(behavior::GoToPose::State s) {
  switch (s) {
    case behavior::GoToPose::State::WaitForPose: return "wait_for_pose";
    case behavior::GoToPose::State::Walk: return "walk";
    case behavior::GoToPose::State::Arrived: return "arrived";
  }
  return "?";
}
const char* calibrateStateName(behavior::CalibrateCameras::State s) {
  using S = behavior::CalibrateCameras::State;
  switch (s) {
    case S::Localize: return "localize";
    case S::GoToPosition: return "go_to_position";
    case S::Align: return "align";
    case S::Turn: return "turn";
    case S::Collect: return "collect";
    case S::Solve: return "solve";
    case S::Apply: return "apply";
    case S::Verify: return "verify";
    case S::Report: return "report";
    case S::Done: return "done";
  }
  return "?";
}
const char* tasksStateName(behavior::ChallengeTasks::State s) {
  using S = behavior::ChallengeTasks::State;
  switch (s) {
    case S::Localize: return "localize";
    case S::FindBall: return "find_ball";
    case S::Search: return "search";
    case S::Approach: return "approach";
    case S::Observe: return "observe";
    case S::Walk: return "walk";
    case S::Verify: return "verify";
    case S::Report: return "report";
    case S::WaitForTap: return "wait_for_tap";
    case S::Done: return "done";
  }
  return "?";
}
const char* lookStateName(behavior::LookActive::State s) {
  switch (s) {
    case behavior::LookActive::State::Sweep: return "sweep";
    case behavior::LookActive::State::LookAtFeature: return "look_at_feature";
    case behavior::LookActive::State::TrackBall: return "track_ball";
    case behavior::LookActive::State::Glance: return "glance";
  }
  return "?";
}
}  // namespace

BehaviorControl::BehaviorControl(const ModuleContext& context)
    : params_(context.load<Params>(name())),
      goTo_(params_.goTo),
      look_(std::make_unique<behavior::LookActive>(FieldModel::from(fieldFor(context)), params_.look)),
      report_(params_.report),
      calibrate_(std::make_unique<behavior::CalibrateCameras>(fieldFor(context), StandController::standPosture(),
                                                              params_.calibrate)),
      tasks_(std::make_unique<behavior::ChallengeTasks>(fieldFor(context), params_.tasks)),
      striker_(std::make_unique<behavior::Striker>(fieldFor(context), params_.striker)) {}

void BehaviorControl::update() {
  const FrameHistory& history = in<FrameHistory>();
  const behavior::BehaviorInput input{history.entries.empty() ? 0.0 : history.entries.back().time,
                                      in<RobotPose>(),
                                      in<BallModel>(),
                                      in<GameState>(),
                                      in<FallState>(),
                                      in<MotionInfo>(),
                                      in<BehaviorCommand>()};
  MotionRequest& motion = out<MotionRequest>();
  HeadMotionRequest& head = out<HeadMotionRequest>();
  SpeechRequest& speech = out<SpeechRequest>();
  CalibrationRequest& calibration = out<CalibrationRequest>();
  calibration = CalibrationRequest{};
  const ChallengeMode& challenge = in<ChallengeMode>();
  if (challenge.modeId != modeId_) {
    modeId_ = challenge.modeId;
    if (params_.acknowledgeModes && challenge.mode == ChallengeMode::Mode::Calibration)
      behavior::say(speech, "Calibration mode");
    else if (params_.acknowledgeModes && challenge.mode == ChallengeMode::Mode::Evaluation)
      behavior::say(speech, "Evaluation mode");
    if (challenge.mode == ChallengeMode::Mode::Calibration) calibrate_->restart(input.time);
    if (challenge.mode == ChallengeMode::Mode::Evaluation) tasks_->restart(input.time);
  }
  const bool calibrating = challenge.mode == ChallengeMode::Mode::Calibration;
  const bool evaluating = challenge.mode == ChallengeMode::Mode::Evaluation;
  // A game: the GameController decides (a commanded walk, e.g. a test's, comes first).
  const bool playing = !calibrating && !evaluating && input.game.fromGameController && !input.command.goTo;
  if (calibrating) {
    behavior::CalibrateCameras::Output c =
        calibrate_->run(input, in<Previous<CalibrationStatus>>(), in<CameraCalibration>(), in<CameraPercepts>());
    motion = c.motion;
    calibration = c.calibration;
    if (c.lookActive) look_->run(input, head);
    else head = c.head;
    if (!c.report.empty()) report_.start(c.report, input.time);
  } else if (evaluating) {
    behavior::ChallengeTasks::Output c = tasks_->run(input, challenge, in<FieldBalls>());
    motion = c.motion;
    if (c.lookActive) look_->run(input, head);
    else head = c.head;
    if (!c.report.empty()) report_.start(c.report, input.time);
  } else if (playing) {
    striker_->run(input, in<BallTracks>(), motion);
    look_->run(input, head);
    if (const auto& at = striker_->lookAt()) {
      // The chosen ball, which the ball model does not follow (yet): look at it.
      head = HeadMotionRequest{};
      head.mode = HeadMotionRequest::Mode::LookAtRobotPoint;
      head.point = Eigen::Vector3d(at->x(), at->y(), 0.05);
      head.camera = at->norm() < params_.look.bottomCameraDistance ? CameraId::Bottom : CameraId::Top;
      head.maxSpeed = params_.look.maxHeadSpeed;
    }
  } else {
    if (input.command.goTo) goTo_.run(input, *input.command.goTo, motion);
    else motion = MotionRequest{};  // stand
    look_->run(input, head);
  }
  // Each option counts its own walk targets, and the motion engine takes a target when the id
  // changes: a new (option, id) pair gets a new id here, so that one option's id never repeats
  // another's last one.
  const int walkSource = calibrating ? 1 : evaluating ? 2 : playing ? 3 : 0;
  if (motion.motion == MotionType::WalkTo) {
    if (walkSource != walkSource_ || motion.walkTargetId != walkOptionId_) {
      walkSource_ = walkSource;
      walkOptionId_ = motion.walkTargetId;
      ++walkId_;
    }
    motion.walkTargetId = walkId_;
  }
  report_.run(input, out<ArmMotionRequest>(), speech);
  if (report_.active()) motion = MotionRequest{};  // a report is made standing
  if (calibrating && report_.state() == behavior::Report::State::Done) calibrate_->reported(input.time);
  if (evaluating && report_.state() == behavior::Report::State::Done) tasks_->reported(input.time);
  debug(kBehavior, [&] {
    return nlohmann::json{{"go_to", input.command.goTo ? goToStateName(goTo_.state()) : "none"},
                          {"look", lookStateName(look_->state())},
                          {"motion", motionTypeName(motion.motion)},
                          {"walk_target", {motion.walkTarget.x, motion.walkTarget.y, motion.walkTarget.theta}},
                          {"head_point", {head.point.x(), head.point.y()}},
                          {"challenge", challengeModeName(challenge.mode)},
                          {"calibrate", calibrating ? calibrateStateName(calibrate_->state()) : "none"},
                          {"tasks", evaluating ? tasksStateName(tasks_->state()) : "none"},
                          {"task", evaluating ? tasks_->summary().task : -1},
                          {"striker", playing ? behavior::strikerStateName(striker_->state()) : "none"},
                          {"kick_choice", playing ? behavior::kickKindName(striker_->lastChoice().kind) : "none"},
                          {"kick_direction", playing ? striker_->lastChoice().direction : 0.0},
                          {"striker_ball", playing && striker_->target() ? nlohmann::json{striker_->target()->x(), striker_->target()->y()} : nlohmann::json()},
                          {"pose", {input.pose.pose.x, input.pose.pose.y, input.pose.pose.theta}},
                          {"calibration_side", calibrating ? calibrate_->summary().side : 0},
                          {"calibration_side_from", calibrating ? calibrate_->summary().sideFrom : ""},
                          {"calibration_request", calibrationActionName(calibration.action)},
                          {"speech", {{"id", speech.id}, {"text", speech.text}}}};
  });
}

NAO_REGISTER_MODULE(BehaviorControl);

}  // namespace nao::modules
