#pragma once
// The robot program: a pipeline of modules over a blackboard, run once per 12 ms cycle
// against any Backend. The same code runs in the simulator and on the NAO. Which module
// provides what comes from config/modules.json, each module's parameters from
// config/parameters/<module>.json (docs/architecture.md).
#include <array>
#include <functional>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "controllers/MotionEngine.h"
#include "controllers/modules/BehaviorControl.h"
#include "controllers/modules/Calibrator.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/infrastructure/CameraImages.h"
#include "representations/motion/HeadJointRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"
#include "representations/perception/CameraMatrices.h"
#include "representations/perception/FallState.h"
#include "representations/perception/TorsoState.h"
#include "robot/Backend.h"
#include "robot/Blackboard.h"
#include "robot/Module.h"

namespace nao {

struct RobotProgramConfig {
  CameraCalibration calibration;  // loaded per robot (head id) at start
  // Walk, kick, get-up parameters instead of config/parameters/MotionEngine.json (a scenario's
  // trial parameters); unset: the files.
  std::optional<MotionEngine::Params> motion;
  // The calibrator's parameters instead of config/parameters/Calibrator.json (calibrate's
  // --solver, --lines, --compare); unset: the file.
  std::optional<modules::Calibrator::Params> calibrator;
  // The behaviour's parameters instead of config/parameters/BehaviorControl.json (match's
  // --opponent baseline); unset: the file.
  std::optional<modules::BehaviorControl::Params> behavior;
  // Holds modules.json, parameters/ and robots/<head id>/. Empty: config/modules.json of the
  // data root and every module with its compiled-in defaults (no parameter files).
  std::string configDir = defaultConfigDir();
  std::string headId;  // selects config/robots/<head id>/ overlays; empty: none
  // Representation -> module, replacing config/modules.json's entries (e.g. an oracle).
  std::map<std::string, std::string> providers;
  // The field the robot plays on (the vision's painted sizes); unset: field_dimensions.json in
  // the configuration folder.
  std::optional<FieldDimensions> field;
  // The operator's command to the behaviour (run --goto): walk to this field pose.
  std::optional<Pose2> goTo;
  // Debug channels for every module and the pipelines' timing (not owned; must outlive the
  // program); null: none. The program sets their time to each cycle's and image's.
  DebugChannels* debug = nullptr;
  // The run's seed for modules that draw random numbers (ModuleContext::seed).
  std::uint64_t seed = 0;

  static std::string defaultConfigDir();
  // For a scenario that drives the robot itself: no behaviour module provides the motion and
  // head requests; the scenario writes them on the motion board.
  void withoutBehavior() {
    providers["MotionRequest"] = "";
    providers["HeadMotionRequest"] = "";
    providers["ArmMotionRequest"] = "";
    providers["SpeechRequest"] = "";
    providers["CalibrationRequest"] = "";
    providers["CalibrationStatus"] = "";  // the calibrator acts on the behaviour's requests only
  }
};

// Two cadences (docs/architecture.md): the motion pipeline runs every cycle; the cognition
// pipeline runs once per camera image, after that cycle's motion, each on its own blackboard.
// What crosses between them is declared (kMotionToCognition, kCognitionToMotion) and copied at
// the cadence boundary: cognition sees motion's state as of the cycle the image arrived in, and
// motion sees cognition's requests from the next cycle on, as it would from another thread.
// In this lock-step form the run is deterministic.
//
// The NAO's threaded form (startCognitionThread): cycle() runs motion only, paced by the
// backend, and hands each new image with a snapshot of the motion-to-cognition exchange (taken
// in the cycle the image arrived) to a cognition thread; cognition hands its requests back and
// motion takes the newest at the start of a cycle. Motion never waits for cognition: the
// hand-offs are swaps under a mutex, and motion skips a request pick-up rather than wait for
// it. When cognition is slower than the cameras, an image not yet taken is replaced by its
// camera's next one (newest wins; droppedImages counts them).
class RobotProgram {
 public:
  // Throws nao::Error for a bad config/modules.json or parameter file (file and key named).
  explicit RobotProgram(const RobotProgramConfig& config = {});
  ~RobotProgram();  // stops the cognition thread; writes the `timing` summary when subscribed
  RobotProgram(const RobotProgram&) = delete;
  RobotProgram& operator=(const RobotProgram&) = delete;

  // One cycle: sensors and images in, motion, joint request out, then cognition per image (in
  // the threaded form: handed to the cognition thread). False when the backend stopped (its
  // stopReason says why). Rethrows what a cognition module threw in the cognition thread.
  bool cycle(Backend& backend);

  // Starts the threaded form (once; before the first cycle). While it runs, the cognition board
  // and the figures below belong to the cognition thread: read them after stopCognitionThread.
  void startCognitionThread();
  // Stops and joins the cognition thread; images not yet taken are discarded. Idempotent; the
  // destructor calls it.
  void stopCognitionThread();
  bool threaded() const { return threaded_ != nullptr; }

  // The motion cadence's board (sensors, motion state, and the requests a scenario sets while
  // no behaviour module provides them), and the cognition cadence's.
  const Blackboard& blackboard() const { return motionBoard_; }
  Blackboard& blackboard() { return motionBoard_; }
  const Blackboard& cognitionBoard() const { return cognitionBoard_; }
  // Motion modules in order, then cognition modules in order.
  std::vector<std::string> moduleOrder() const;
  const Pipeline& pipeline() const { return motion_; }
  const Pipeline& cognitionPipeline() const { return cognition_; }
  // Cognition runs so far, per camera, and images skipped for a timestamp older than the last.
  const std::array<long, kNumCameras>& cognitionRuns() const { return cognitionRuns_; }
  long skippedImages() const { return skippedImages_; }
  // Wall time of the last cycle's motion (pipeline and answer) and of its cognition runs (ms).
  struct CycleTiming {
    double motionMs = 0;
    std::vector<double> cognitionMs;
  };
  const CycleTiming& lastTiming() const { return timing_; }
  // Called after each cognition run with its image and the cognition board (a scenario's
  // scorer reads the estimates there; it must not write).
  using CognitionObserver = std::function<void(const CameraImage& image, const Blackboard& cognition)>;
  void setCognitionObserver(CognitionObserver observer) { observer_ = std::move(observer); }
  // Threaded form: images replaced by a newer one of their camera before cognition took them.
  std::array<long, kNumCameras> droppedImages() const;
  // Cognition's time per image: wall and thread CPU (ms), summed, and the largest wall time.
  struct CognitionTime {
    double wallMsSum = 0, wallMsMax = 0, cpuMsSum = 0;
  };
  const CognitionTime& cognitionTime() const { return cognitionTime_; }

 private:
  using Copy = void (*)(const Blackboard& from, Blackboard& to);
  struct Crossing {
    RepresentationType type;
    Copy copy;
  };
  // Cognition for one image, with motion's side of the exchange read from `exchange`.
  void runCognition(const Blackboard& exchange, const CameraImage& image);
  void cognitionLoop();
  void handOff(const CameraImage& image);

  // One image and the exchange as of the cycle it arrived in.
  struct Job {
    CameraImage image;
    Blackboard exchange;
  };
  // The threaded form's hand-offs. Job buffers are swapped, never reallocated, once warm.
  struct Threads {
    std::thread cognition;
    std::mutex jobsMutex;  // pending, full, stop, dropped
    std::condition_variable wake;
    std::array<Job, kNumCameras> pending;
    std::array<bool, kNumCameras> full{};
    bool stop = false;
    std::array<long, kNumCameras> dropped{};
    std::array<Job, kNumCameras> staging;  // motion thread's
    Job working;                           // cognition thread's
    std::mutex requestsMutex;              // requests, fresh
    Blackboard requests;                   // cognition's side of the exchange, newest
    bool fresh = false;
    std::atomic<bool> failed{false};
    std::exception_ptr error;  // set before failed
  };

  Blackboard motionBoard_, cognitionBoard_;
  Pipeline motion_, cognition_;
  std::vector<Crossing> toCognition_, toMotion_;  // the declared exchange, as far as provided
  std::array<long, kNumCameras> cognitionRuns_{};
  std::array<double, kNumCameras> lastImageTime_{};
  long skippedImages_ = 0;
  CognitionObserver observer_;
  CycleTiming timing_;
  DebugChannels* debug_ = nullptr;
  CognitionTime cognitionTime_;
  std::array<ExposureWeights, kNumCameras> sentExposureWeights_;  // the backend's (its default at start)
  std::unique_ptr<Threads> threaded_;
};

}  // namespace nao
