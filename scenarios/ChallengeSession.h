#pragma once
// The simulated venue of the Autonomous Calibration Challenge with the referee's hands and
// eyes (../shared/reference/calibration-challenge.md): one robot program that has never been
// calibrated, on a NAO with injected camera offsets, two balls; the referee places the robot
// and the balls, holds the camera shield over the cameras, presses the buttons, taps the head,
// listens to what the robot says, watches its arm (truth: a hand above the head) and judges
// the termination rules (ChallengeReferee). Nothing here moves the robot while it plays.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "controllers/RobotProgram.h"
#include "controllers/modules/Calibrator.h"
#include "representations/perception/CameraPercepts.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "robot/Debug.h"
#include "scenarios/ChallengeReferee.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::sim {

class World;
class SimBackend;
class CameraRenderer;

struct ChallengeSetup {
  FieldDimensions field;
  std::string robotModel;                  // empty: models/nao_v6.xml
  CameraCalibration miscalibration;        // injected into the simulated hardware
  Lighting lighting;
  int side = -1;                           // the start: right (-1, y < 0) or left (+1) side line
  std::uint64_t seed = 1;
  bool randomize = false;                  // a foreign robot: masses, joint offsets (head aside), floor friction
  std::optional<double> floorFriction;     // the venue's carpet (after randomize's)
  VenueLook venue;                         // how the venue looks (sim/VenueLook.h)
  std::optional<modules::Calibrator::Params> calibrator;  // the robot's Calibrator parameters (else its file)
  DebugChannels* debug = nullptr;          // the robot program's debug channels (not owned)
};

// What the referee heard with an arm up.
struct ChallengeReport {
  double t = 0;  // s, simulated
  std::string text;
};

class ChallengeSession {
 public:
  explicit ChallengeSession(const ChallengeSetup& setup);
  ~ChallengeSession();

  World& world() { return *world_; }
  const World& world() const { return *world_; }
  RobotProgram& program() { return *program_; }
  const std::string& headId() const { return headId_; }
  double time() const;
  nlohmann::json robotJson() const { return robot_; }

  // The referee's hands.
  void placeRobot();  // standing at the start (side line, in line with the own penalty mark)
  void placeBalls(const std::array<Eigen::Vector2d, 2>& balls);
  void setShield(bool on);
  // Runs robot cycles for `seconds` (fewer after a termination).
  void runFor(double seconds);
  // Chest + head front (calibration) or head rear (evaluation) held 1.2 s; returns the
  // simulated time at which the hold reached 1 s (the robot's rule fires, the phase clock starts).
  double startMode(bool evaluation);
  // A head tap (the middle button for 0.2 s): the next task.
  void tap();
  // Runs until the robot says something with an arm up (returned), a termination, or the
  // simulated time `deadline` (nullopt for both).
  std::optional<ChallengeReport> untilReport(double deadline);

  // The referee's eyes.
  const std::string& terminated() const { return referee_.terminated(); }
  int falls() const { return referee_.falls(); }
  void note(const std::string& kind, const std::string& text);
  const std::vector<ChallengeEvent>& events() const { return events_; }
  double pathLength() const { return pathLength_; }
  double maxStep() const { return maxStep_; }
  // Every robot pose of the truth, one per 0.1 s, and the robot's belief then (for pictures).
  struct Track {
    double t;
    Eigen::Vector3d truth, belief;
    bool beliefValid;
  };
  const std::vector<Track>& track() const { return track_; }

  // Each camera's last image with its percepts, kept from the moment this is called (for the
  // pictures of what the robot saw when it reported).
  struct View {
    CameraImage image;
    CameraPercepts percepts;
  };
  void keepLastViews();
  const std::array<std::optional<View>, 2>& lastViews() const { return *lastViews_; }

  // Observers of the cognition runs (the scorers' captures); called in order.
  void addCognitionObserver(RobotProgram::CognitionObserver observer) { observers_.push_back(std::move(observer)); }
  std::function<void(double simTime)> progress;  // about once per simulated second

 private:
  void cycle();

  ChallengeSetup setup_;
  std::unique_ptr<World> world_;
  std::unique_ptr<SimBackend> backend_;
  std::unique_ptr<CameraRenderer> renderer_;
  std::unique_ptr<RobotProgram> program_;
  std::string headId_;
  nlohmann::json robot_;
  std::mt19937_64 noiseRng_;
  bool shield_ = false;
  ChallengeReferee referee_;
  std::vector<ChallengeEvent> events_;
  std::vector<RobotProgram::CognitionObserver> observers_;
  int lastSpeech_ = 0;
  bool armWasUp_ = false;
  std::optional<ChallengeReport> pendingReport_;
  double pathLength_ = 0, maxStep_ = 0, nextProgress_ = 0, nextTrack_ = 0;
  std::vector<Track> track_;
  std::shared_ptr<std::array<std::optional<View>, 2>> lastViews_ = std::make_shared<std::array<std::optional<View>, 2>>();
};

}  // namespace nao::sim
