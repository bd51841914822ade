#include "scenarios/ChallengeReferee.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/World.h"

namespace nao::sim {

bool ChallengeReferee::leftField(const World& world, int robot) {
  const FieldDimensions& f = world.field().dims;
  const double maxX = f.length / 2 + f.lineWidth / 2, maxY = f.width / 2 + f.lineWidth / 2;
  for (const Eigen::Vector3d& c : world.soleCorners(robot))
    if (std::abs(c.x()) <= maxX && std::abs(c.y()) <= maxY) return false;
  return true;
}

namespace {
// The torso's tilt from upright, deg.
double torsoTiltDeg(const World& world, int robot) {
  return std::acos(std::clamp(world.torsoPose(robot).linear()(2, 2), -1.0, 1.0)) * 180 / M_PI;
}
}  // namespace

bool ChallengeReferee::armRaised(const World& world, int robot) const {
  if (torsoTiltDeg(world, robot) > params_.upTilt) return false;
  const double headZ = world.cameraPose(robot, CameraId::Top).translation().z();
  return world.handPosition(robot, false).z() > headZ || world.handPosition(robot, true).z() > headZ;
}

const std::string& ChallengeReferee::check(World& world, int robot, std::vector<ChallengeEvent>& events) {
  if (!terminated_.empty()) return terminated_;
  const double t = world.time();
  auto terminate = [&](const std::string& reason, const std::string& text) {
    events.push_back({t, "termination", reason + ": " + text});
    terminated_ = reason;
  };
  for (const World::BallContact& c : world.takeBallContacts()) {
    if (c.robot != robot) continue;
    const Eigen::Vector3d b = world.ballPosition(c.ball);
    char text[96];
    std::snprintf(text, sizeof text, "ball %d at (%.2f, %.2f)", c.ball, b.x(), b.y());
    events.push_back({c.time, "ball_contact", text});
    if (terminated_.empty()) terminate("touched_ball", text);
  }
  if (!terminated_.empty()) return terminated_;

  const double tilt = torsoTiltDeg(world, robot);
  const double z = world.torsoPose(robot).translation().z();
  if (fallenSince_ < 0 && (tilt > params_.fallTilt || z < params_.fallHeight)) {
    fallenSince_ = t;
    ++falls_;
    events.push_back({t, "fall", "fall " + std::to_string(falls_)});
    if (falls_ >= params_.maxFalls) {
      terminate("three_falls", "fall " + std::to_string(falls_));
      return terminated_;
    }
  } else if (fallenSince_ >= 0 && tilt < params_.upTilt && z > params_.upHeight) {
    events.push_back({t, "get_up", "standing again after " + std::to_string(t - fallenSince_) + " s"});
    fallenSince_ = -1;
  } else if (fallenSince_ >= 0 && t - fallenSince_ > params_.getUpLimit) {
    terminate("not_up_within_60s", "fallen at " + std::to_string(fallenSince_) + " s");
    return terminated_;
  }
  if (leftField(world, robot)) {
    const Eigen::Vector3d p = world.robotPose(robot);
    char text[64];
    std::snprintf(text, sizeof text, "at (%.2f, %.2f)", p.x(), p.y());
    events.push_back({t, "left_field", text});
    terminate("left_field", text);
  }
  return terminated_;
}

}  // namespace nao::sim
