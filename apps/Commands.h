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
// apps/RunNao.cpp. readImage: decodes a PNG/JPEG for --cameras files:DIR (sim::readImage in
// nao-soccer; nao-soccer-robot has no image decoding and refuses files:).
using ImageFileReader = std::function<CameraImage(const std::string& path, CameraId camera)>;
int runNao(const RunOptions& o, ImageFileReader readImage = {});
int benchSimCommand(const BenchSimOptions& o);
int benchProgramCommand(const BenchProgramOptions& o);
int benchPerceptionCommand(const BenchPerceptionOptions& o);
int benchCalibrationCommand(const BenchCalibrationOptions& o);
int perceiveCommand(const PerceiveOptions& o);
int evalPerceptionCommand(const EvalPerceptionOptions& o);
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
int modulesCommand(const ModulesOptions& o);

}  // namespace nao::cli
