#pragma once
// The values of every command's options, filled by the declarations in
// apps/cli/Declarations.cpp (which hold their ranges, units and defaults).
#include <cstdint>
#include <string>
#include <vector>

#include "apps/cli/CommandLine.h"

namespace nao::cli {

// Simulator settings: lighting, injected miscalibration, the robot's MJCF.
struct SimOptions {
  std::string lighting = "default";
  std::string miscalibration = "none";     // none, random, or "numbers": miscalibrationDeg
  std::vector<double> miscalibrationDeg;  // body, top, bottom roll and pitch (deg)
  std::string model;                    // "" = models/nao_v6.xml
  std::string venue = "none";           // --venue: none, random or a name (sim/VenueLook.h)
};

// --debug CHANNEL[,CHANNEL] and --debug-out FILE (robot/Debug.h).
struct DebugOptions {
  std::string channels;  // "" = none
  std::string out;       // "" = stderr
};

struct RenderOptions {
  CommonOptions common;
  SimOptions sim;
  std::string camera = "top", view = "camera", out;
  std::string cameraMatrix;  // --camera-matrix FILE: the twin of a recorded real image
  std::vector<double> pose, head, ball;
};

struct NaoRunOptions {
  std::string lolaSocket = "/tmp/robocup";
  std::string cameraTop = "/dev/video-top", cameraBottom = "/dev/video-bottom", cameraSettings;
  int team = 0, player = 1, gcPort = 3838, gcReturnPort = 3939;
  std::string gcAddress = "0.0.0.0";
  std::string clock = "monotonic";  // or "lola": 12 ms per LoLA packet
  bool lockstep = false;            // one packet at a time, deterministic (--lockstep)
  std::string speechCommand = "flite -t";  // the text-to-speech command, the text appended ("none": log only)
  std::string record;               // the calibration log, written when the run ends (--record)
};

struct RunOptions {
  CommonOptions common;
  SimOptions sim;
  NaoRunOptions nao;
  std::string backend = "sim", cameras, images;
  double seconds = 10;
  std::vector<double> pose, goTo, ball;
  DebugOptions debug;
};

struct BenchSimOptions {
  CommonOptions common;
  std::string lighting = "default", model;
  std::string venue = "none";
  double seconds = 20;
  int repeats = 3;
  bool profile = false;
};

struct BenchProgramOptions {
  CommonOptions common;
  std::string lighting = "default", model;
  double seconds = 20;
  int repeats = 3;
  std::vector<double> goTo{0, 0, 0};  // X, Y (m), THETA (deg): the behaviour's walk target
  bool perModule = false;
};

struct BenchMatchOptions {
  CommonOptions common;
  std::string lighting = "default", percepts = "both";  // vision, oracle, or both side by side
  double seconds = 20;
  int repeats = 3;
};

struct BenchPerceptionOptions {
  CommonOptions common;
  std::string lighting = "default", camera = "top";
  int frames = 300, repeats = 3;
};

struct BenchCalibrationOptions {
  CommonOptions common;
  SimOptions sim;
  int repeats = 3;
  double timeLimit = 600;
};

struct PerceiveOptions {
  CommonOptions common;
  std::string image, camera = "top", out;
  std::string cameraMatrix;  // --camera-matrix FILE: a recorded camera matrix (RecordedCameraMatrix)
  std::vector<double> head, torso;
  int width = 0, height = 0;  // of a raw YUYV file; 0: from its length
  int scale = 1;
  DebugOptions debug;
};

struct EvalPerceptionOptions {
  CommonOptions common;
  std::string lighting = "sweep", images, failures;
  std::string venue = "random";
  std::string percepts = "vision", fitOracle;  // --percepts, --fit-oracle FILE
  int trials = 300, imagesEvery = 25;
  double maxOffset = 1;
  DebugOptions debug;
};

struct EvalRealOptions {
  CommonOptions common;
  std::string dir, failures;
};

struct EvalCalibrationOptions {
  CommonOptions common;
  std::string lighting = "sweep", solver = "gauss-newton", rows;
  std::string venue = "random";
  std::string images;  // --images DIR: each trial's views in DIR/seed_S/
  bool randomize = false;
  int trials = 100;
  double maxOffset = 3, timeLimit = 600;
  std::vector<std::uint64_t> seeds;  // --seeds: exactly these trials
  DebugOptions debug;
};

struct EvalLocalizationOptions {
  CommonOptions common;
  std::string lighting = "sweep", rows;
  std::string percepts = "vision";
  int trials = 8, kidnapEvery = 4, rollEvery = 4;
  std::vector<std::uint64_t> seeds;  // --seeds: exactly these trials
  double seconds = 20;
  bool randomize = false;
  DebugOptions debug;
};

struct EvalChallengeOptions {
  CommonOptions common;
  std::string lighting = "sweep", rows, model, venue = "none";
  int trials = 100;
  std::vector<std::uint64_t> seeds;  // --seeds: exactly these trials
  double maxOffset = 3, timeLimit = 600;
  bool randomize = false, skipCalibration = false;
};

struct EvalMotionOptions {  // eval walk, walk-to, getup
  CommonOptions common;
  int trials = 20;
  double seconds = 60;
  bool randomize = false;
  DebugOptions debug;  // eval walk only
};

struct WalkOptions {
  CommonOptions common;
  double vx = 0, vy = 0, vtheta = 0, seconds = 10;
  std::vector<double> to;
  bool randomize = false;
  DebugOptions debug;
};

struct KickOptions {
  CommonOptions common;
  int trials = 20;
  bool randomize = false;
};

struct TrainBallOptions {
  CommonOptions common;
  int scenes = 1500, lightings = 2, hidden = 16, iterations = 200;
  std::string samples, out;
};

struct TrainFrictionOptions {
  CommonOptions common;
  int rolls = 16;
  double minSpeed = 0.5, maxSpeed = 2;
};

struct CalibrateOptions {
  CommonOptions common;
  SimOptions sim;
  DebugOptions debug;
  std::string solver, lines;  // empty: config/parameters/Calibrator.json's, as the robot program
  std::string start = "right", images, store;
  std::string record, fromLog, headId;
  bool compare = false, save = false;
  double timeLimit = 600;
};

struct ChallengeCommandOptions {
  CommonOptions common;
  SimOptions sim{"default", "random", {}, ""};
  DebugOptions debug;
  std::string start = "seed", images, venue = "none", record;
  bool randomize = false, skipCalibration = false;
  double timeLimit = 600, maxOffset = 3;
};

struct MatchOptions {
  CommonOptions common;
  SimOptions sim;
  double seconds = 0;      // 0 (not given): the whole game
  double halfSeconds = 300;
  bool randomize = false;
  std::string opponent = "self", replay, situation, images;
  std::string percepts = "vision";
  DebugOptions debug;  // the home robot program's channels
  std::string gc = "inprocess";
  int gcPort = 3838, gcReturnPort = 3939;
};

struct EvalMatchOptions {
  CommonOptions common;
  int games = 20;
  std::vector<std::uint64_t> seeds;  // --seeds: exactly these games
  double halfSeconds = 300, seconds = 0;  // seconds 0: whole games
  bool randomize = false;
  std::string opponent = "baseline", lighting = "sweep", model, rows;
  std::string percepts = "vision";
};

struct BatchOptions {
  CommonOptions common;
  std::string runner = "local", dir, sshlogin;
  int chunk = 0, jobs = 0;  // 0: the evaluation's own chunk size; one job per core
  bool resume = false;
  std::vector<std::string> evalArgs;  // "eval", the target, its options (what batch did not take)
};

struct ModulesOptions {
  CommonOptions common;
  bool dot = false;
};

struct Options {
  RenderOptions render;
  RunOptions run;
  BenchSimOptions benchSim;
  BenchProgramOptions benchProgram;
  BenchMatchOptions benchMatch;
  BenchPerceptionOptions benchPerception;
  BenchCalibrationOptions benchCalibration;
  PerceiveOptions perceive;
  EvalPerceptionOptions evalPerception;
  EvalRealOptions evalReal;
  EvalCalibrationOptions evalCalibration;
  EvalLocalizationOptions evalLocalization;
  EvalChallengeOptions evalChallenge;
  EvalMatchOptions evalMatch;
  EvalMotionOptions evalWalk, evalWalkTo, evalGetUp;
  WalkOptions walk;
  KickOptions kick;
  TrainBallOptions trainBall;
  TrainFrictionOptions trainFriction;
  CalibrateOptions calibrate;
  ChallengeCommandOptions challenge;
  MatchOptions match;
  ModulesOptions modules;
  BatchOptions batch;
};

}  // namespace nao::cli
