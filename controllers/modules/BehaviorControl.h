#pragma once
// Cognition: the behaviour. Options (controllers/behavior/, one per file, each a small state
// machine) turn the models into the motion and head requests. The default behaviour: stand (the
// motion engine gets up after a fall by itself), localize, look around actively, and walk to
// the commanded field pose (BehaviorCommand::goTo) by the self-localization. When the referee
// starts a challenge mode (ChallengeMode), the robot says so; in the calibration mode it
// calibrates its cameras (CalibrateCameras, talking to the Calibrator through
// CalibrationRequest and the status the Calibrator left in the last run); in the evaluation
// mode it does the five tasks (ChallengeTasks: the balls of FieldBalls, the walks). While a
// GameController runs a game (GameState::fromGameController) it plays (Striker).
#include <memory>

#include "controllers/behavior/CalibrateCameras.h"
#include "controllers/behavior/ChallengeTasks.h"
#include "controllers/behavior/GoToPose.h"
#include "controllers/behavior/LookActive.h"
#include "controllers/behavior/Report.h"
#include "controllers/behavior/Striker.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "representations/behavior/BehaviorCommand.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/infrastructure/GameState.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/BallTracks.h"
#include "representations/modeling/FieldBalls.h"
#include "representations/modeling/RobotPose.h"
#include "representations/motion/MotionInfo.h"
#include "representations/perception/CalibrationStatus.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/perception/FallState.h"
#include "perception/CameraCalibration.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class BehaviorControl
    : public Module<BehaviorControl,
                    Requires<RobotPose, BallModel, GameState, FallState, MotionInfo, BehaviorCommand, FrameHistory,
                             ChallengeMode, CameraCalibration, CameraPercepts, FieldBalls, BallTracks,
                             Previous<CalibrationStatus>>,
                    Provides<MotionRequest, HeadMotionRequest, ArmMotionRequest, SpeechRequest, CalibrationRequest>,
                    Cadence::Cognition> {
 public:
  struct Params {
    behavior::GoToPose::Params goTo;
    behavior::LookActive::Params look;
    behavior::Report::Params report;
    behavior::CalibrateCameras::Params calibrate;
    behavior::ChallengeTasks::Params tasks;
    behavior::Striker::Params striker;
    bool acknowledgeModes = true;  // say "Calibration mode" / "Evaluation mode" when the referee starts one
  };

  explicit BehaviorControl(const ModuleContext& context = {});
  const behavior::GoToPose& goTo() const { return goTo_; }
  const behavior::LookActive& look() const { return *look_; }
  const behavior::Report& report() const { return report_; }
  const behavior::CalibrateCameras& calibrate() const { return *calibrate_; }
  const behavior::ChallengeTasks& tasks() const { return *tasks_; }
  const behavior::Striker& striker() const { return *striker_; }

 private:
  void update() override;

  Params params_;
  behavior::GoToPose goTo_;
  std::unique_ptr<behavior::LookActive> look_;
  behavior::Report report_;
  std::unique_ptr<behavior::CalibrateCameras> calibrate_;
  std::unique_ptr<behavior::ChallengeTasks> tasks_;
  std::unique_ptr<behavior::Striker> striker_;
  int modeId_ = 0;  // the last ChallengeMode start acknowledged
  int walkSource_ = -1, walkOptionId_ = 0, walkId_ = 0;  // the walk target ids sent (see update)
};

}  // namespace nao::modules

namespace nao {
template <class V>
void describe(V& v, modules::BehaviorControl::Params& p) {
  v("goTo", p.goTo);
  v("look", p.look);
  v("report", p.report);
  v("calibrate", p.calibrate);
  v("tasks", p.tasks);
  v("striker", p.striker);
  v("acknowledgeModes", p.acknowledgeModes);
}
}  // namespace nao
