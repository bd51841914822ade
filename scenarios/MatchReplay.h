#pragma once
// A match's replay (`match --replay F.html`): one self-contained HTML page (no network, no
// external script) with the field from above, both robots' true poses and the poses they
// believe, the balls' true positions and each robot's modelled ball, the score and the
// GameController's state, and the event log as a timeline; play, pause, scrub, click an event
// to jump to it. The page's URL fragment #t=SECONDS opens it paused at that time (what the
// headless-browser test uses); the body's data-frames, data-events and data-errors attributes
// say what it loaded and how many script errors it met, data-canvas where the field lies on
// the page (left,top in pixels).
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"

namespace nao::sim {

// One moment of the game, in the field frame.
struct ReplayFrame {
  double t = 0;
  std::string state;
  std::array<int, 2> score{};
  struct Robot {
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // truth: x, y, theta
    bool penalised = false;
    bool beliefValid = false;
    Eigen::Vector3d belief = Eigen::Vector3d::Zero();  // the robot's own pose estimate
    bool ballValid = false;
    Eigen::Vector2d ball = Eigen::Vector2d::Zero();    // the robot's ball model
  };
  std::array<Robot, 2> robots;
  std::vector<Eigen::Vector2d> balls;  // truth
};

// The replay's data: field, frames (compact arrays; "layout" names their entries), events.
nlohmann::json replayData(const FieldDimensions& field, const std::vector<ReplayFrame>& frames, const nlohmann::json& events);
// The page for replayData's JSON.
std::string replayHtml(const nlohmann::json& data);

// Where the page draws a field point: pixels from the canvas's top left (x right, y down).
Eigen::Vector2d replayPixel(const FieldDimensions& field, const Eigen::Vector2d& p);
inline constexpr double kReplayPixelsPerMetre = 100;

}  // namespace nao::sim
