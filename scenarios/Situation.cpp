#include "scenarios/Situation.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "robot/Error.h"

namespace nao::sim {

namespace {

constexpr double kDeg = M_PI / 180;
const std::set<std::string> kActions = {"walk_to", "stand", "sit", "fall", "lie", "get_up", "kick", "none"};

// Checks one JSON object's keys and reads its values, naming the path of a bad one.
class Reader {
 public:
  Reader(const std::string& file, const nlohmann::json& j, std::string where) : file_(file), j_(j), where_(std::move(where)) {
    if (!j_.is_object()) fail("", "must be an object");
  }
  void allow(std::initializer_list<const char*> keys) const {
    std::set<std::string> known(keys.begin(), keys.end());
    for (const auto& [key, value] : j_.items())
      if (!known.count(key)) fail(key, "unknown key");
  }
  bool has(const char* key) const { return j_.contains(key); }
  const nlohmann::json& at(const char* key) const {
    if (!j_.contains(key)) fail(key, "missing");
    return j_.at(key);
  }
  double number(const char* key, double lo, double hi) const {
    const nlohmann::json& v = at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(key, "must be a number");
    const double x = v.get<double>();
    if (x < lo || x > hi) fail(key, "must be in " + range(lo, hi));
    return x;
  }
  std::string text(const char* key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_string()) fail(key, "must be a string");
    return v.get<std::string>();
  }
  bool flag(const char* key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_boolean()) fail(key, "must be true or false");
    return v.get<bool>();
  }
  // [x, y] or [x, y, theta_deg] in metres (and degrees) within +-limit.
  Eigen::VectorXd numbers(const char* key, std::size_t n, double limit) const {
    const nlohmann::json& v = at(key);
    if (!v.is_array() || v.size() != n) fail(key, "must be " + std::to_string(n) + " numbers");
    Eigen::VectorXd out(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) fail(key, "must be " + std::to_string(n) + " numbers");
      out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
      const double lim = i == 2 ? 360 : limit;
      if (std::abs(out[static_cast<Eigen::Index>(i)]) > lim) fail(key, "each within +-" + range(0, lim).substr(3));
    }
    return out;
  }
  int team(const char* key) const {
    const std::string t = text(key);
    if (t != "home" && t != "away") fail(key, "must be home or away");
    return t == "home" ? 0 : 1;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw Error(file_, where_ + (key.empty() ? "" : (where_.empty() ? "" : ".") + key) + ": " + problem);
  }
  const std::string& where() const { return where_; }

 private:
  static std::string range(double lo, double hi) {
    char b[64];
    std::snprintf(b, sizeof b, "%g..%g", lo, hi);
    return b;
  }
  const std::string& file_;
  const nlohmann::json& j_;
  std::string where_;
};

Eigen::Vector3d pose(const Eigen::VectorXd& v) { return {v[0], v[1], v[2] * kDeg}; }

}  // namespace

Situation loadSituation(const std::string& path, double halfSeconds) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(path, std::string("not JSON: ") + e.what());
  }
  Situation s;
  const Reader r(path, j, "");
  r.allow({"state", "secs_remaining", "seconds", "half", "field", "robots", "balls"});
  if (r.has("state")) {
    const std::string state = r.text("state");
    bool known = false;
    for (gc::State st : {gc::State::Initial, gc::State::Ready, gc::State::Set, gc::State::Playing})
      if (state == gc::stateName(st)) {
        s.state = st;
        known = true;
      }
    if (!known) r.fail("state", "must be INITIAL, READY, SET or PLAYING");
  }
  if (r.has("secs_remaining")) s.secsRemaining = r.number("secs_remaining", 1, halfSeconds);
  if (r.has("seconds")) s.seconds = r.number("seconds", 0.1, 3600);
  if (r.has("half")) s.firstHalf = r.number("half", 1, 2) < 1.5;
  if (r.has("field")) s.field = r.text("field");
  if (r.has("robots")) {
    const nlohmann::json& robots = r.at("robots");
    if (!robots.is_array() || robots.size() > 2) r.fail("robots", "must be a list of at most 2 robots");
    for (std::size_t i = 0; i < robots.size(); ++i) {
      const Reader rr(path, robots[i], "robots[" + std::to_string(i) + "]");
      rr.allow({"team", "pose", "program", "script"});
      SituationRobot& robot = s.robots[static_cast<std::size_t>(rr.team("team"))];
      if (robot.present) rr.fail("team", "two robots of one team");
      robot.present = true;
      robot.pose = pose(rr.numbers("pose", 3, 20));
      if (rr.has("program")) robot.program = rr.flag("program");
      if (!rr.has("script")) continue;
      if (robot.program) rr.fail("script", "a robot runs its program or a script, not both");
      const nlohmann::json& script = rr.at("script");
      if (!script.is_array()) rr.fail("script", "must be a list of steps");
      double last = 0;
      for (std::size_t k = 0; k < script.size(); ++k) {
        const Reader rs(path, script[k], rr.where() + ".script[" + std::to_string(k) + "]");
        rs.allow({"t", "do", "pose", "direction_deg", "speed_m_s"});
        SituationStep step;
        step.t = rs.number("t", 0, 3600);
        if (step.t < last) rs.fail("t", "steps must come in time order");
        last = step.t;
        step.action = rs.text("do");
        if (!kActions.count(step.action)) rs.fail("do", "unknown action '" + step.action + "' (walk_to, stand, sit, fall, lie, get_up, kick, none)");
        if (step.action == "walk_to") step.pose = pose(rs.numbers("pose", 3, 20));
        else if (rs.has("pose")) rs.fail("pose", "only for walk_to");
        if (step.action == "kick") {
          step.directionDeg = rs.number("direction_deg", -360, 360);
          step.speed = rs.number("speed_m_s", 0.1, 10);
        } else if (rs.has("direction_deg") || rs.has("speed_m_s")) {
          rs.fail(rs.has("direction_deg") ? "direction_deg" : "speed_m_s", "only for kick");
        }
        robot.script.push_back(step);
      }
    }
  }
  if (r.has("balls")) {
    const nlohmann::json& balls = r.at("balls");
    if (!balls.is_array() || balls.size() > 4) r.fail("balls", "must be a list of at most 4 balls");
    for (std::size_t i = 0; i < balls.size(); ++i) {
      const Reader rb(path, balls[i], "balls[" + std::to_string(i) + "]");
      rb.allow({"position", "velocity", "at", "by"});
      SituationBall b;
      b.position = rb.numbers("position", 2, 20);
      if (rb.has("velocity")) {
        b.velocity = Eigen::Vector2d(rb.numbers("velocity", 2, 10));
        b.at = rb.has("at") ? rb.number("at", 0, 3600) : 0.0;
        b.by = rb.has("by") ? rb.team("by") : -1;
      } else if (rb.has("at") || rb.has("by")) {
        rb.fail(rb.has("at") ? "at" : "by", "only with a velocity");
      }
      s.balls.push_back(b);
    }
  }
  return s;
}

}  // namespace nao::sim
