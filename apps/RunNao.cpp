// nao-soccer run --backend nao: the same robot program as in the simulator, against LoLA's
// socket and the V4L2 cameras, with the GameController and the buttons on the blackboard.
#include "apps/Cli.h"
#include "apps/Commands.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "controllers/RobotProgram.h"
#include "perception/calibration/CalibrationStore.h"
#include "perception/FieldDimensions.h"
#include "perception/vision/BallClassifier.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "robot/nao/GameController.h"
#include "robot/nao/NaoBackend.h"

namespace nao::cli {
namespace {

void logLine(const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); }

// --camera-settings FILE: {"top": {"width": 640, "height": 480, "auto_exposure": false,
// "exposure": 100, "gain": 32, "auto_white_balance": false, "white_balance": 4500}, "bottom": {...}}
void applyCameraSettings(const std::string& path, std::array<V4l2CameraConfig, kNumCameras>& cameras) {
  std::ifstream f(path);
  if (!f) throw Error(path, "cannot open");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(f);
  } catch (const std::exception& e) {
    throw Error(path, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw Error(path, "expected an object with 'top' and/or 'bottom'");
  for (const auto& [name, value] : j.items()) {
    if (name != "top" && name != "bottom") throw Error(path, name + ": unknown camera (top or bottom)");
    if (!value.is_object()) throw Error(path, name + ": expected an object");
    V4l2CameraConfig& c = cameras[name == "top" ? 0 : 1];
    for (const auto& [key, v] : value.items()) {
      const std::string field = name + "." + key;
      auto integer = [&](int lo, int hi) {
        if (!v.is_number_integer() || v.get<long>() < lo || v.get<long>() > hi)
          throw Error(path, field + ": expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
        return v.get<int>();
      };
      auto boolean = [&] {
        if (!v.is_boolean()) throw Error(path, field + ": expected true or false");
        return v.get<bool>();
      };
      if (key == "width") c.width = integer(2, 4096);
      else if (key == "height") c.height = integer(1, 4096);
      else if (key == "auto_exposure") c.controls.autoExposure = boolean();
      else if (key == "exposure") c.controls.exposure = integer(0, 1 << 20);
      else if (key == "gain") c.controls.gain = integer(0, 1 << 16);
      else if (key == "auto_white_balance") c.controls.autoWhiteBalance = boolean();
      else if (key == "white_balance") c.controls.whiteBalance = integer(1000, 12000);
      else throw Error(path, field + ": unknown setting");
    }
    if (c.width % 2 != 0) throw Error(path, name + ".width: must be even (YUYV pairs)");
  }
}

// The motion cadence (this thread: one cycle per LoLA packet) at a real-time priority where the
// OS allows it (root, CAP_SYS_NICE, or an rtprio limit such as the NAO images' LimitRTPRIO=36):
// SCHED_FIFO 10, below LoLA and HAL (SCHED_FIFO 20/30 on the HULKs' image), like the teams'
// motion threads. One line either way.
void useRealTimePriority() {
  constexpr int kPriority = 10;
  sched_param p{};
  p.sched_priority = kPriority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (err == 0) {
    logLine("run: motion cadence at real-time priority (SCHED_FIFO " + std::to_string(kPriority) + ")");
  } else {
    logLine("run: motion cadence at normal priority: SCHED_FIFO " + std::to_string(kPriority) + " not allowed (" +
            std::strerror(err) + "; needs CAP_SYS_NICE or an rtprio limit, e.g. LimitRTPRIO=36 in the unit)");
  }
}

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

}  // namespace

int runNao(const RunOptions& options) {
  const NaoRunOptions& nao = options.nao;
  std::optional<double> seconds;
  if (options.common.has("--seconds")) seconds = options.seconds;
  NaoBackendConfig config;
  config.lolaSocket = nao.lolaSocket;
  config.cameras = options.cameras != "none";
  config.camera[0].device = nao.cameraTop;
  config.camera[1].device = nao.cameraBottom;
  if (!nao.cameraSettings.empty()) applyCameraSettings(nao.cameraSettings, config.camera);

  GameController::Config gcConfig;
  gcConfig.team = nao.team;
  gcConfig.player = nao.player;
  gcConfig.port = static_cast<std::uint16_t>(nao.gcPort);
  gcConfig.returnPort = static_cast<std::uint16_t>(nao.gcReturnPort);
  gcConfig.bindAddress = nao.gcAddress;

  // The field this robot plays on: a wrong file stops the start, not the game.
  const std::string fieldPath = options.common.field.empty() ? dataPath("config/field_dimensions.json") : options.common.field;
  const FieldDimensions field = FieldDimensions::load(fieldPath);
  char size[64];
  std::snprintf(size, sizeof size, " (%.2f x %.2f m)", field.length, field.width);
  logLine("run: field " + fieldPath + size);
  if (gcConfig.team == 0) logLine("run: no --team: GameController packets will be ignored");
  // The ball classifier's weights: a missing or broken file stops the start too.
  vision::defaultBallClassifier();
  DebugSink debug(options.debug);  // opened before LoLA: a bad --debug-out stops the start

  NaoBackend::installSignalHandlers();
  useRealTimePriority();
  GameController gameController(gcConfig, logLine);
  NaoBackend backend(config, logLine);
  RobotProgramConfig programConfig;
  programConfig.field = field;
  if (options.goTo.size() == 3) programConfig.goTo = Pose2(options.goTo[0], options.goTo[1], options.goTo[2] * M_PI / 180);
  programConfig.debug = debug.channels();
  RobotProgram program(programConfig);
  ButtonInterface buttons;
  Blackboard& bb = program.blackboard();
  // Soft while the robot tips over and for its first second on the ground; after that the
  // ramp hands the joints back to the program (its get-up motion).
  backend.setFallMonitor([&bb]() -> std::string {
    if (!bb.has<FallState>()) return {};
    const FallState& f = bb.read<FallState>();
    const double lying = f.fallen ? bb.read<SensorFrame>().time - f.fallTime : 0;
    if (!f.falling && !(f.fallen && lying < 1.0)) return {};
    return std::string(f.fallen ? "fallen" : "falling") + " (" + fallDirectionName(f.direction) + ")";
  });

  // The camera calibration stored for this head (config/calibration/<head id>.json), read as
  // soon as LoLA has told the head id. A broken file is logged and the offsets stay zero: a
  // wrong calibration must not stop the robot.
  bool calibrationLoaded = false;
  // CPU time per cadence (this thread's, so waiting for LoLA's next packet does not count): the
  // budget a team sees on the Atom.
  double cpuSumMs = 0, cpuMaxMs = 0;
  std::uint64_t cpuCycles = 0;
  double cpuStart = threadCpuMs();
  while (true) {
    const double cpuNow = threadCpuMs();
    if (cpuCycles++ > 0) {
      cpuSumMs += cpuNow - cpuStart;
      cpuMaxMs = std::max(cpuMaxMs, cpuNow - cpuStart);
    }
    cpuStart = cpuNow;
    bb.write<GameState>() = gameController.state();
    bb.write<LedRequest>().chest = chestColour(gameController.state());
    if (!program.cycle(backend)) break;
    if (!calibrationLoaded && backend.robotInfo().headId != "unknown") {
      calibrationLoaded = true;
      try {
        const calibration::CalibrationStore store;
        if (const auto record = store.load(backend.robotInfo().headId)) {
          bb.write<CameraCalibration>() = record->offsets;
          logLine("run: camera calibration " + store.pathFor(backend.robotInfo().headId));
        } else {
          logLine("run: no camera calibration for head " + backend.robotInfo().headId + " yet (offsets 0)");
        }
      } catch (const std::exception& e) {
        logLine(std::string("run: camera calibration not used: ") + e.what());
      }
    }
    const SensorFrame& frame = bb.read<SensorFrame>();
    const ButtonState& pressed = buttons.update(frame.touch, frame.time);
    bb.write<ButtonState>() = pressed;
    for (ButtonEvent e : pressed.events) {
      logLine(std::string("buttons: ") + buttonEventName(e));
      switch (e) {
        case ButtonEvent::ChestPress:
          if (backend.safety().currentFault() == SafetyFault::User) backend.safety().resume("chest button");
          else gameController.chestButton(frame.time);
          break;
        case ButtonEvent::Unstiffen:
          backend.safety().fault(SafetyFault::User, "head buttons held: unstiffened (chest button to stiffen again)");
          break;
        case ButtonEvent::StartCalibration:
        case ButtonEvent::StartCalibrationEvaluation:
          break;  // on the blackboard (ButtonState) for the calibration behaviour
      }
    }
    gameController.receive(frame.time);
    gc::ReturnData ret;
    ret.playerNum = static_cast<std::uint8_t>(gcConfig.player);
    ret.teamNum = static_cast<std::uint8_t>(gcConfig.team);
    ret.fallen = bb.has<FallState>() && bb.read<FallState>().fallen ? 1 : 0;
    gameController.sendReturnIfDue(frame.time, ret);
    if (seconds && frame.time >= *seconds) {
      char text[64];
      std::snprintf(text, sizeof text, "--seconds %g reached", *seconds);
      backend.requestStop(text);
    }
  }

  const auto& s = backend.stats();
  const double meanMs = s.cycles ? s.sumAnswerMs / static_cast<double>(s.cycles) : 0;
  std::fprintf(stderr,
               "run: stopped: %s; %llu cycles, answers within %.2f ms (mean %.2f ms), %llu late, %llu corrupt "
               "packets, %llu stale periods, %llu skipped\n",
               backend.stopReason().c_str(), static_cast<unsigned long long>(s.cycles), s.maxAnswerMs, meanMs,
               static_cast<unsigned long long>(s.late), static_cast<unsigned long long>(s.corrupt),
               static_cast<unsigned long long>(s.staleEvents), static_cast<unsigned long long>(s.skipped));
  const double cpuMeanMs = cpuCycles > 1 ? cpuSumMs / static_cast<double>(cpuCycles - 1) : 0;
  std::fprintf(stderr, "run: CPU per cycle: mean %.3f ms, max %.3f ms (of the 12 ms cadence)\n", cpuMeanMs, cpuMaxMs);
  if (!options.common.json.empty()) {
    const GameState& g = gameController.state();
    writeJson(options.common.json,
              {{"backend", "nao"},
               {"cycles", s.cycles},
               {"packets", s.packets},
               {"corrupt_packets", s.corrupt},
               {"stale_periods", s.staleEvents},
               {"skipped_packets", s.skipped},
               {"late_answers", s.late},
               {"max_answer_ms", s.maxAnswerMs},
               {"mean_answer_ms", meanMs},
               {"cpu_ms_per_cycle", {{"mean", cpuMeanMs}, {"max", cpuMaxMs}}},
               {"stop_reason", backend.stopReason()},
               {"clean_stop", backend.stoppedCleanly()},
               {"robot", {{"body_id", backend.robotInfo().bodyId}, {"head_id", backend.robotInfo().headId}}},
               {"game", {{"state", gc::stateName(g.state)}, {"penalised", g.penalised()},
                         {"from_gamecontroller", g.fromGameController}, {"rejected_packets", gameController.rejected()}}}});
  }
  return backend.stoppedCleanly() ? 0 : 1;
}

}  // namespace nao::cli
