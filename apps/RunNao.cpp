// nao-soccer run --backend nao: the same robot program as in the simulator, against LoLA's
// socket and the V4L2 cameras (or image files), in its threaded form: motion in this thread,
// paced by LoLA, cognition in its own. The app keeps the infrastructure: the GameController's
// UDP socket, the backend's safety; what they say goes onto the board for the modules.
#include "apps/Cli.h"
#include "apps/Commands.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <chrono>
#include <fstream>
#include <future>
#include <memory>

#include "controllers/CalibrationLogging.h"
#include "controllers/RobotProgram.h"
#include "representations/modeling/BallModel.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/modeling/RobotPose.h"
#include "perception/calibration/CalibrationStore.h"
#include "perception/calibration/Solver.h"
#include "representations/perception/CalibrationStatus.h"
#include "perception/FieldDimensions.h"
#include "perception/vision/BallClassifier.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/infrastructure/SafetyState.h"
#include "robot/nao/FileCamera.h"
#include "robot/nao/GameController.h"
#include "robot/nao/ImageDecoder.h"
#include "robot/nao/ImageFiles.h"
#include "robot/nao/NaoBackend.h"
#include "robot/nao/SocketCamera.h"
#include "robot/nao/SpeechOutput.h"

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
    for (const auto& item : value.items()) {
      const std::string& key = item.key();
      const auto& v = item.value();
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

// What cognition saw, per camera: a team reads at a glance whether the vision works at a venue.
struct PerceptTally {
  long processed = 0, withLines = 0, lines = 0, balls = 0, fieldBoundary = 0;
  nlohmann::json json() const {
    return {{"processed", processed}, {"with_lines", withLines}, {"lines", lines}, {"balls", balls},
            {"field_boundary", fieldBoundary}};
  }
};

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double monotonicSeconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The camera calibration stored for this head (config/calibration/<head id>.json). A broken
// file is logged and the offsets stay zero: a wrong calibration must not stop the robot.
CameraCalibration storedCalibration(const std::string& headId) {
  try {
    const calibration::CalibrationStore store;
    if (const auto record = store.load(headId)) {
      logLine("run: camera calibration " + store.pathFor(headId));
      return record->offsets;
    }
    logLine("run: no camera calibration for head " + headId + " yet (offsets 0)");
  } catch (const std::exception& e) {
    logLine(std::string("run: camera calibration not used: ") + e.what());
  }
  return {};
}

// Stores what the Calibrator applied (config/calibration/<head id>.json). A refused or failed
// write is logged: the robot goes on with the applied offsets.
void storeCalibration(const std::string& headId, const CalibrationStatus& status) {
  try {
    calibration::CalibrationRecord record;
    record.offsets = status.applied;
    record.rmsAngleDeg = status.rmsAngleDeg;
    record.rmsDepthM = status.rmsDepthM;
    record.samples = status.samples[0] + status.samples[1];
    record.solver = calibration::solverName(calibration::SolverKind::GaussNewton);
    record.converged = status.converged;
    const calibration::SaveOutcome saved = calibration::CalibrationStore().save(headId, record);
    logLine(saved.saved ? "calibration: stored " + saved.path : "calibration: not stored: " + saved.reason);
  } catch (const std::exception& e) {
    logLine(std::string("calibration: not stored: ") + e.what());
  }
}

}  // namespace

int runNao(const RunOptions& options) {
  const NaoRunOptions& nao = options.nao;
  std::optional<double> seconds;
  if (options.common.has("--seconds")) seconds = options.seconds;
  NaoBackendConfig config;
  config.lolaSocket = nao.lolaSocket;
  config.cameras = options.cameras != "none";
  config.lolaClock = nao.clock == "lola";
  // --lockstep: a replay peer sends the next packet only after the answer, so a slow cycle
  // (the program's build, a sanitizer) is not a stale stream.
  if (nao.lockstep) config.staleCycles = 1000000;
  // --clock lola (a simulator slower than real time): its physics stands still while it renders
  // or the machine stalls, so a wall-time gap leaves no robot unattended; a dead peer is still
  // noticed, after half a second.
  else if (config.lolaClock) config.staleCycles = 42;
  config.camera[0].device = nao.cameraTop;
  config.camera[1].device = nao.cameraBottom;
  if (!nao.cameraSettings.empty()) applyCameraSettings(nao.cameraSettings, config.camera);
  // --cameras files:DIR: the images of DIR/top/ and DIR/bottom/ through the backend's camera
  // hand-off instead of V4L2 (the folders were checked with the command line).
  if (options.cameras.rfind("files:", 0) == 0) {
    const std::string dir = options.cameras.substr(6);
    // On the LoLA clock in lockstep (the first frame with the first packet), else the monotonic one.
    const double start = nao.lockstep ? 0.0 : monotonicSeconds();
    std::string counts;
    for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
      std::vector<std::string> files = imageFilesIn(dir + "/" + cameraName(cam));
      counts += (counts.empty() ? "" : ", ") + std::to_string(files.size()) + " " + cameraName(cam);
      config.sources[static_cast<int>(cam)] =
          std::make_shared<FileCamera>(cam, std::move(files), decodeImageFile, start, kCameraPeriod, logLine, nao.lockstep);
    }
    logLine("run: cameras from the files in " + dir + " (" + counts + "), 30 Hz each, looping");
  }
  // --cameras socket:PATH: frames a simulator renders and sends (tests/sim_lola_peer).
  if (options.cameras.rfind("socket:", 0) == 0) {
    const std::string path = options.cameras.substr(7);
    for (CameraId cam : {CameraId::Top, CameraId::Bottom})
      config.sources[static_cast<int>(cam)] = std::make_shared<SocketCamera>(cam, path, logLine);
    logLine("run: cameras from the frames sent over " + path);
  }

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
  GameController gameController(gcConfig, logLine);
  // The robot's voice: each new SpeechRequest goes to the text-to-speech command, off this thread.
  SpeechOutput speech(nao.speechCommand == "none" ? std::string() : nao.speechCommand, logLine);
  int utterances = 0;
  NaoBackend backend(config, logLine);
  auto stopAfterSeconds = [&](double time) {
    if (!seconds || time < *seconds) return;
    char text[64];
    std::snprintf(text, sizeof text, "--seconds %g reached", *seconds);
    backend.requestStop(text);
  };

  // The robot program is built once LoLA's first packet has told the head id: its parameters
  // with config/robots/<head id>/ over them, and the head's stored camera calibration. It is
  // built in a thread of its own while every packet is answered soft in place (the stiffness
  // ramp starts when the program takes over), so that no answer waits for the build.
  std::unique_ptr<RobotProgram> program;
  std::future<std::unique_ptr<RobotProgram>> building;
  double programStart = 0, lastFrameTime = 0;  // the program's clock
  SensorFrame first;
  while (!program && backend.waitForSensors(first)) {
    if (!building.valid()) {
      RobotProgramConfig programConfig;
      const std::string headId = backend.robotInfo().headId;
      const std::string overlay = programConfig.configDir + "/robots/" + headId;
      // A head id that cannot name a folder (never a NAO's) must not stop the robot: no overlay.
      const bool usable = !headId.empty() && std::all_of(headId.begin(), headId.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
      });
      if (usable) programConfig.headId = headId;
      logLine(!usable ? "run: head id '" + escapeControl(headId) + "' names no folder: no per-robot parameters"
              : std::filesystem::is_directory(overlay) ? "run: parameters with this head's " + overlay + "/"
                                                       : "run: no per-robot parameters for head " + headId + " (" +
                                                             overlay + "/)");
      programConfig.calibration = storedCalibration(headId);
      programConfig.field = field;
      if (options.goTo.size() == 3)
        programConfig.goTo = Pose2(options.goTo[0], options.goTo[1], options.goTo[2] * M_PI / 180);
      programConfig.debug = debug.channels();
      if (nao.lockstep) {  // built before the first answer: the same packets meet the same program
        program = std::make_unique<RobotProgram>(programConfig);
        programStart = first.time;
        backend.answerSoftInPlace();
        break;
      }
      building = std::async(std::launch::async,
                            [programConfig] { return std::make_unique<RobotProgram>(programConfig); });
    }
    backend.answerSoftInPlace();
    stopAfterSeconds(first.time);
    if (building.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      program = building.get();  // a bad parameter file throws here: one line, exit 2
      programStart = first.time;
    }
  }
  if (!program && building.valid()) building.get();  // stopped while building: its error, if any

  // CPU time of the motion cadence (this thread's, so waiting for LoLA's next packet does not
  // count): the budget a team sees on the Atom. Cognition measures its own thread.
  nlohmann::json beliefs = nlohmann::json::array();
  std::array<PerceptTally, kNumCameras> seen{};
  std::unique_ptr<CalibrationRecorder> recorder;  // --record
  double cpuSumMs = 0, cpuMaxMs = 0;
  std::uint64_t cpuCycles = 0;
  if (program) {
    Blackboard& bb = program->blackboard();
    // Soft while the robot tips over and for its first second on the ground; after that the
    // ramp hands the joints back to the program (its get-up motion).
    backend.setFallMonitor([&bb]() -> std::string {
      if (!bb.has<FallState>()) return {};
      const FallState& f = bb.read<FallState>();
      const double lying = f.fallen ? bb.read<SensorFrame>().time - f.fallTime : 0;
      if (!f.falling && !(f.fallen && lying < 1.0)) return {};
      return std::string(f.fallen ? "fallen" : "falling") + " (" + fallDirectionName(f.direction) + ")";
    });
    // The belief once a second of image time, for the JSON: pose and ball as cognition left them
    // after that image (the cognition thread writes, this one reads after it has stopped).
    // A calibration the robot program applied (its Calibrator) is stored for this head, here in
    // the cognition thread, never in the LoLA loop; the next start loads it.
    const std::string storeHead = backend.robotInfo().headId;
    if (!nao.record.empty()) recorder = std::make_unique<CalibrationRecorder>(storeHead, "nao");
    program->setCognitionObserver([&beliefs, &seen, next = 0.0, storedId = 0, storeHead, rec = recorder.get()](
                                      const CameraImage& image, const Blackboard& cognition) mutable {
      if (rec) rec->observe(image, cognition);
      if (cognition.has<CalibrationStatus>() && cognition.read<CalibrationStatus>().appliedId != storedId) {
        const CalibrationStatus& c = cognition.read<CalibrationStatus>();
        storedId = c.appliedId;
        storeCalibration(storeHead, c);
      }
      if (cognition.has<CameraPercepts>()) {
        const CameraPercepts& p = cognition.read<CameraPercepts>();
        PerceptTally& t = seen[static_cast<int>(p.camera)];
        t.processed += p.processed;
        t.withLines += !p.lines.empty();
        t.lines += static_cast<long>(p.lines.size());
        t.balls += p.ball.seen;
        t.fieldBoundary += p.fieldBoundary.valid;
      }
      if (image.timestamp < next || !cognition.has<RobotPose>()) return;
      next = std::floor(image.timestamp) + 1;
      const RobotPose& pose = cognition.read<RobotPose>();
      nlohmann::json b = {{"image_time", image.timestamp},
                          {"camera", cameraName(image.camera)},
                          {"estimated_pose", {pose.pose.x, pose.pose.y, pose.pose.theta * 180 / M_PI}},
                          {"valid", pose.valid},
                          {"sigma_m", pose.sigmaTranslation()}};
      if (cognition.has<BallModel>()) {
        const BallModel& ball = cognition.read<BallModel>();
        b["ball"] = {{"valid", ball.valid}, {"lost", ball.lost}, {"position", {ball.position.x(), ball.position.y()}}};
      }
      beliefs.push_back(std::move(b));
    });
    // Cognition in a thread of its own; started before this thread becomes real-time, so that
    // it keeps the normal policy (threads inherit it). In lockstep it runs in each motion cycle
    // after the answer, as in the simulator.
    if (!nao.lockstep) program->startCognitionThread();
    useRealTimePriority();
    GameState lastGame;
    int lastChallengeId = 0, lastSpeechId = 0;
    double time = first.time;
    double cpuStart = threadCpuMs();
    while (true) {
      const double cpuNow = threadCpuMs();
      if (cpuCycles++ > 0) {
        cpuSumMs += cpuNow - cpuStart;
        cpuMaxMs = std::max(cpuMaxMs, cpuNow - cpuStart);
      }
      cpuStart = cpuNow;
      // What the program's GameStateProvider and LedControl turn into the game state and the
      // chest LED: the receiver's view and the safety's user unstiffen.
      const bool gcActive = gameController.gameControllerActive(time);
      bb.write<GameControllerData>() = GameControllerData{gcActive, gameController.state()};
      bb.write<SafetyState>().userUnstiffened = backend.safety().currentFault() == SafetyFault::User;
      if (!program->cycle(backend)) break;
      const SensorFrame& frame = bb.read<SensorFrame>();
      time = lastFrameTime = frame.time;
      if (bb.has<ButtonState>()) {
        for (ButtonEvent e : bb.read<ButtonState>().events) {
          logLine(std::string("buttons: ") + buttonEventName(e));
          if (e == ButtonEvent::ChestPress && backend.safety().currentFault() == SafetyFault::User)
            backend.safety().resume("chest button");
          else if (e == ButtonEvent::ChestPress && gcActive)
            logLine("game: chest button ignored, the GameController decides");
          else if (e == ButtonEvent::Unstiffen)
            backend.safety().fault(SafetyFault::User, "head buttons held: unstiffened (chest button to stiffen again)");
          // StartCalibration, StartCalibrationEvaluation, HeadTap: ChallengeModeProvider's
        }
      }
      if (bb.has<ChallengeMode>() && bb.read<ChallengeMode>().modeId != lastChallengeId) {
        lastChallengeId = bb.read<ChallengeMode>().modeId;
        logLine(std::string("challenge: ") + challengeModeName(bb.read<ChallengeMode>().mode) + " mode");
      }
      if (bb.has<SpeechRequest>() && bb.read<SpeechRequest>().id != lastSpeechId) {
        lastSpeechId = bb.read<SpeechRequest>().id;
        speech.say(bb.read<SpeechRequest>().text);
        ++utterances;
      }
      const GameState& game = bb.read<GameState>();
      if (!game.fromGameController && (game.state != lastGame.state || game.penalty != lastGame.penalty))
        logLine(std::string("game: ") + gc::stateName(game.state) + (game.penalised() ? ", penalised" : "") +
                " (chest button)");
      lastGame = game;
      gameController.receive(frame.time);
      gc::ReturnData ret;
      ret.playerNum = static_cast<std::uint8_t>(gcConfig.player);
      ret.teamNum = static_cast<std::uint8_t>(gcConfig.team);
      ret.fallen = bb.has<FallState>() && bb.read<FallState>().fallen ? 1 : 0;
      gameController.sendReturnIfDue(frame.time, ret);
      stopAfterSeconds(frame.time);
    }
    if (!nao.lockstep) program->stopCognitionThread();
    backend.setFallMonitor({});
  }

  const auto& s = backend.stats();
  const double meanMs = s.answered ? s.sumAnswerMs / static_cast<double>(s.answered) : 0;
  const double p99Ms = s.answerMsQuantile(0.99);
  std::fprintf(stderr,
               "run: stopped: %s; %llu cycles, %llu answered, answers within %.2f ms (mean %.2f, p99 %.2f ms), "
               "%llu late, %llu corrupt packets, %llu stale periods, %llu skipped\n",
               backend.stopReason().c_str(), static_cast<unsigned long long>(s.cycles),
               static_cast<unsigned long long>(s.answered), s.maxAnswerMs, meanMs, p99Ms,
               static_cast<unsigned long long>(s.late), static_cast<unsigned long long>(s.corrupt),
               static_cast<unsigned long long>(s.staleEvents), static_cast<unsigned long long>(s.skipped));
  const double cpuMeanMs = cpuCycles > 1 ? cpuSumMs / static_cast<double>(cpuCycles - 1) : 0;
  std::fprintf(stderr, "run: motion CPU per cycle: mean %.3f ms, max %.3f ms (of the 12 ms cadence)\n", cpuMeanMs,
               cpuMaxMs);
  std::array<long, kNumCameras> processed{}, dropped{};
  long skippedImages = 0, images = 0;
  RobotProgram::CognitionTime cognition;
  if (program) {
    processed = program->cognitionRuns();
    dropped = program->droppedImages();
    skippedImages = program->skippedImages();
    cognition = program->cognitionTime();
  }
  for (long n : processed) images += n;
  const double runSeconds = std::max(1e-9, lastFrameTime - programStart);
  const double cognitionMeanMs = images ? cognition.wallMsSum / static_cast<double>(images) : 0;
  const double cognitionCpuMs = images ? cognition.cpuMsSum / static_cast<double>(images) : 0;
  std::fprintf(stderr,
               "run: cognition: %ld top + %ld bottom images (%.1f + %.1f per s), %ld + %ld dropped (newer image "
               "waiting), %.2f ms per image (max %.2f, CPU %.2f)\n",
               processed[0], processed[1], static_cast<double>(processed[0]) / runSeconds,
               static_cast<double>(processed[1]) / runSeconds, dropped[0], dropped[1], cognitionMeanMs,
               cognition.wallMsMax, cognitionCpuMs);
  if (recorder) {
    recorder->write(nao.record);
    logLine("run: calibration log " + nao.record + " (" + std::to_string(recorder->log().records.size()) + " views)");
  }
  if (!options.common.json.empty()) {
    const GameState& g = program ? program->blackboard().read<GameState>() : gameController.state();
    nlohmann::json j = {
        {"backend", "nao"},
        {"cycles", s.cycles},
        {"packets", s.packets},
        {"corrupt_packets", s.corrupt},
        {"stale_periods", s.staleEvents},
        {"skipped_packets", s.skipped},
        {"late_answers", s.late},
        {"max_answer_ms", s.maxAnswerMs},
        {"mean_answer_ms", meanMs},
        {"lola", {{"cycles", s.cycles}, {"answered", s.answered}, {"late", s.late}, {"cycle_ms_p99", p99Ms},
                  {"late_answer_times", s.lateAnswers}}},
        {"cpu_ms_per_cycle", {{"mean", cpuMeanMs}, {"max", cpuMaxMs}}},
        {"images_processed", {{"top", processed[0]}, {"bottom", processed[1]}}},
        {"images_dropped", {{"top", dropped[0]}, {"bottom", dropped[1]}}},
        {"images_skipped", skippedImages},
        {"percepts", {{"top", seen[0].json()}, {"bottom", seen[1].json()}}},
        {"cognition",
         {{"ms_per_image", {{"mean", cognitionMeanMs}, {"max", cognition.wallMsMax}}},
          {"cpu_ms_per_image", cognitionCpuMs},
          {"images_per_s", {{"top", static_cast<double>(processed[0]) / runSeconds},
                            {"bottom", static_cast<double>(processed[1]) / runSeconds}}}}},
        {"modules", program ? program->moduleOrder() : std::vector<std::string>{}},
        {"cadences",
         {{"motion", program ? program->pipeline().order() : std::vector<std::string>{}},
          {"cognition", program ? program->cognitionPipeline().order() : std::vector<std::string>{}}}},
        {"stop_reason", backend.stopReason()},
        {"clock", nao.clock},
        {"per_second", beliefs},
        {"clean_stop", backend.stoppedCleanly()},
        {"robot", {{"body_id", backend.robotInfo().bodyId}, {"head_id", backend.robotInfo().headId}}},
        {"speech", {{"command", nao.speechCommand}, {"utterances", utterances}, {"spoken", speech.spoken()},
                    {"failed", speech.failed()}}},
        {"game", {{"state", gc::stateName(g.state)}, {"penalised", g.penalised()},
                  {"from_gamecontroller", g.fromGameController}, {"rejected_packets", gameController.rejected()}}}};
    // CLOCK_MONOTONIC of the program's time 0: lines its times up with another clock.
    if (nao.clock == "monotonic") j["clock_origin_s"] = backend.clockOrigin();
    // What the robot believed at the end (the cognition thread has stopped): no truth here.
    if (program && program->cognitionBoard().has<RobotPose>()) {
      const RobotPose& pose = program->cognitionBoard().read<RobotPose>();
      j["final_estimated_pose"] = {pose.pose.x, pose.pose.y, pose.pose.theta * 180 / M_PI};
      j["final_estimate_valid"] = pose.valid;
      j["final_estimate_sigma_m"] = pose.sigmaTranslation();
    }
    if (program && program->cognitionBoard().has<BallModel>()) {
      const BallModel& ball = program->cognitionBoard().read<BallModel>();
      j["final_ball"] = {{"valid", ball.valid}, {"lost", ball.lost}, {"position", {ball.position.x(), ball.position.y()}}};
    }
    writeJson(options.common.json, j);
  }
  return backend.stoppedCleanly() ? 0 : 1;
}

}  // namespace nao::cli
