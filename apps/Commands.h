#pragma once
// The bodies of the nao-soccer commands. Each gets its parsed options (apps/cli/Options.h,
// declared and bounded in apps/cli/Declarations.cpp) and returns the exit code: 0 success,
// 1 a failed run; bad input throws nao::Error (exit 2).
#include <functional>
#include <string>

#include "apps/cli/Options.h"
#include "robot/CameraImage.h"

namespace nao::cli {

int renderCommand(const RenderOptions& o);
int runCommand(const RunOptions& o);
// apps/RunNao.cpp: the same in nao-soccer and nao-soccer-robot.
int runNao(const RunOptions& o);
int benchSimCommand(const BenchSimOptions& o);
int benchProgramCommand(const BenchProgramOptions& o);
int benchMatchCommand(const BenchMatchOptions& o);
int benchPerceptionCommand(const BenchPerceptionOptions& o);
int benchCalibrationCommand(const BenchCalibrationOptions& o);
int perceiveCommand(const PerceiveOptions& o);
int evalPerceptionCommand(const EvalPerceptionOptions& o);
int evalRealCommand(const EvalRealOptions& o);
int evalCalibrationCommand(const EvalCalibrationOptions& o);
int evalLocalizationCommand(const EvalLocalizationOptions& o);  // apps/LocalizationCommand.cpp
int evalWalkCommand(const EvalMotionOptions& o);
int evalWalkToCommand(const EvalMotionOptions& o);
int evalGetUpCommand(const EvalMotionOptions& o);
int walkCommand(const WalkOptions& o);
int kickCommand(const KickOptions& o);
int trainBallCommand(const TrainBallOptions& o);
int trainFrictionCommand(const TrainFrictionOptions& o);
int calibrateCommand(const CalibrateOptions& o);
int challengeCommand(const ChallengeCommandOptions& o);
int matchCommand(const MatchOptions& o);
int evalChallengeCommand(const EvalChallengeOptions& o);
int evalMatchCommand(const EvalMatchOptions& o);
int modulesCommand(const ModulesOptions& o);
int batchCommand(const BatchOptions& o);  // apps/BatchCommand.cpp

}  // namespace nao::cli
