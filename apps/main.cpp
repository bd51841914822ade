// nao-soccer: one command for the simulator, the evaluations and the robot program. The command
// line is declared in apps/cli/; this file binds each command to its body. How the process ends
// (exit codes, the one-line errors, output files only after a run without error) is
// CommandLine::main's.
#include <string>

#include <opencv2/core/utils/logger.hpp>

#include "apps/Commands.h"
#include "apps/cli/CommandLine.h"
#include "sim/GlContext.h"

namespace {

using nao::cli::CommandLine;

void bind(CommandLine& cl) {
  auto& o = cl.options();
  auto to = [&](const std::string& path, auto body, const auto& options) {
    cl.command(path)->run = [body, &options] {
      nao::sim::setGlApi(*nao::sim::parseGlApi(options.common.gl));
      return body(options);
    };
  };
  to("render", nao::cli::renderCommand, o.render);
  to("run", nao::cli::runCommand, o.run);
  to("bench sim", nao::cli::benchSimCommand, o.benchSim);
  to("bench program", nao::cli::benchProgramCommand, o.benchProgram);
  to("bench match", nao::cli::benchMatchCommand, o.benchMatch);
  to("bench perception", nao::cli::benchPerceptionCommand, o.benchPerception);
  to("bench calibration", nao::cli::benchCalibrationCommand, o.benchCalibration);
  to("perceive", nao::cli::perceiveCommand, o.perceive);
  to("eval perception", nao::cli::evalPerceptionCommand, o.evalPerception);
  to("eval real", nao::cli::evalRealCommand, o.evalReal);
  to("eval calibration", nao::cli::evalCalibrationCommand, o.evalCalibration);
  to("eval localization", nao::cli::evalLocalizationCommand, o.evalLocalization);
  to("eval challenge", nao::cli::evalChallengeCommand, o.evalChallenge);
  to("eval match", nao::cli::evalMatchCommand, o.evalMatch);
  to("eval walk", nao::cli::evalWalkCommand, o.evalWalk);
  to("eval walk-to", nao::cli::evalWalkToCommand, o.evalWalkTo);
  to("eval getup", nao::cli::evalGetUpCommand, o.evalGetUp);
  to("walk", nao::cli::walkCommand, o.walk);
  to("kick", nao::cli::kickCommand, o.kick);
  to("train ball", nao::cli::trainBallCommand, o.trainBall);
  to("train friction", nao::cli::trainFrictionCommand, o.trainFriction);
  to("calibrate", nao::cli::calibrateCommand, o.calibrate);
  to("calibration-challenge", nao::cli::challengeCommand, o.challenge);
  to("match", nao::cli::matchCommand, o.match);
  to("modules", nao::cli::modulesCommand, o.modules);
  to("batch", nao::cli::batchCommand, o.batch);
}

}  // namespace

int main(int argc, char** argv) {
  // OpenCV's own log lines would break the one-line errors; failures reach us as exceptions.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  CommandLine cl;
  bind(cl);
  return cl.main(argc, argv);
}
