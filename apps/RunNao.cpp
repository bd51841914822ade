// nao-soccer run --backend nao: the same robot program as in the simulator, against LoLA's
// socket and the V4L2 cameras, with the GameController and the buttons on the blackboard.
#include "apps/RunNao.h"

#include <cmath>
#include <cstdio>
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

long ranged(const Args& args, const std::string& name, long fallback, long lo, long hi) {
  const long v = args.integer(name, fallback);
  if (v < lo || v > hi)
    throw Error("--" + name, std::to_string(v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

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

}  // namespace

std::vector<Option> naoRunOptions() {
  return {{"lola-socket", "PATH", "nao: LoLA's Unix socket (default /tmp/robocup)"},
          {"camera-top", "DEV", "nao: top camera device (default /dev/video-top)"},
          {"camera-bottom", "DEV", "nao: bottom camera device (default /dev/video-bottom)"},
          {"camera-settings", "FILE", "nao: camera resolution, exposure, gain, white balance (JSON)"},
          {"team", "N", "nao: team number for the GameController (0 = none, default)"},
          {"player", "N", "nao: player number 1..20 (default 1)"},
          {"gc-port", "N", "nao: GameController UDP port (default 3838)"},
          {"gc-return-port", "N", "nao: port of the return packets (default 3939)"},
          {"gc-address", "IP", "nao: address to receive GameController packets on (default 0.0.0.0)"}};
}

int runNao(const Args& args) {
  const std::string cameras = args.str("cameras", "v4l2");
  if (cameras != "none" && cameras != "v4l2") throw Error("--cameras", "must be none or v4l2 with --backend nao");
  std::optional<double> seconds;
  if (args.has("seconds")) {
    seconds = args.num("seconds", 0);
    if (!(*seconds > 0)) throw Error("--seconds", "must be > 0");
  }
  NaoBackendConfig config;
  config.lolaSocket = args.str("lola-socket", "/tmp/robocup");
  config.cameras = cameras == "v4l2";
  config.camera[0].device = args.str("camera-top", config.camera[0].device);
  config.camera[1].device = args.str("camera-bottom", config.camera[1].device);
  if (args.has("camera-settings")) applyCameraSettings(args.str("camera-settings", ""), config.camera);

  GameController::Config gcConfig;
  gcConfig.team = static_cast<int>(ranged(args, "team", 0, 0, 254));
  gcConfig.player = static_cast<int>(ranged(args, "player", 1, 1, gc::kMaxPlayers));
  gcConfig.port = static_cast<std::uint16_t>(ranged(args, "gc-port", gc::kPort, 1, 65535));
  gcConfig.returnPort = static_cast<std::uint16_t>(ranged(args, "gc-return-port", gc::kReturnPort, 1, 65535));
  gcConfig.bindAddress = args.str("gc-address", "0.0.0.0");

  // The field this robot plays on: a wrong file stops the start, not the game.
  const std::string fieldPath = args.str("field", dataPath("config/field_dimensions.json"));
  const FieldDimensions field = FieldDimensions::load(fieldPath);
  char size[64];
  std::snprintf(size, sizeof size, " (%.2f x %.2f m)", field.length, field.width);
  logLine("run: field " + fieldPath + size);
  if (gcConfig.team == 0) logLine("run: no --team: GameController packets will be ignored");
  // The ball classifier's weights: a missing or broken file stops the start too.
  vision::defaultBallClassifier();

  NaoBackend::installSignalHandlers();
  GameController gameController(gcConfig, logLine);
  NaoBackend backend(config, logLine);
  RobotProgram program;
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
  while (true) {
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
    if (seconds && frame.time >= *seconds) backend.requestStop("--seconds " + args.str("seconds", "") + " reached");
  }

  const auto& s = backend.stats();
  const double meanMs = s.cycles ? s.sumAnswerMs / static_cast<double>(s.cycles) : 0;
  std::fprintf(stderr,
               "run: stopped: %s; %llu cycles, answers within %.2f ms (mean %.2f ms), %llu late, %llu corrupt "
               "packets, %llu stale periods, %llu skipped\n",
               backend.stopReason().c_str(), static_cast<unsigned long long>(s.cycles), s.maxAnswerMs, meanMs,
               static_cast<unsigned long long>(s.late), static_cast<unsigned long long>(s.corrupt),
               static_cast<unsigned long long>(s.staleEvents), static_cast<unsigned long long>(s.skipped));
  if (args.has("json")) {
    const GameState& g = gameController.state();
    writeJson(args.str("json", "-"),
              {{"backend", "nao"},
               {"cycles", s.cycles},
               {"packets", s.packets},
               {"corrupt_packets", s.corrupt},
               {"stale_periods", s.staleEvents},
               {"skipped_packets", s.skipped},
               {"late_answers", s.late},
               {"max_answer_ms", s.maxAnswerMs},
               {"mean_answer_ms", meanMs},
               {"stop_reason", backend.stopReason()},
               {"clean_stop", backend.stoppedCleanly()},
               {"robot", {{"body_id", backend.robotInfo().bodyId}, {"head_id", backend.robotInfo().headId}}},
               {"game", {{"state", gc::stateName(g.state)}, {"penalised", g.penalised()},
                         {"from_gamecontroller", g.fromGameController}, {"rejected_packets", gameController.rejected()}}}});
  }
  return backend.stoppedCleanly() ? 0 : 1;
}

}  // namespace nao::cli
