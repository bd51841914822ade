#include "robot/nao/Safety.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nao {

const char* safetyFaultName(SafetyFault f) {
  switch (f) {
    case SafetyFault::None: return "none";
    case SafetyFault::CorruptPacket: return "corrupt packet";
    case SafetyFault::StaleSensors: return "stale sensor data";
    case SafetyFault::Fall: return "fall";
    case SafetyFault::BadRequest: return "bad joint request";
    case SafetyFault::User: return "unstiffened by the user";
    case SafetyFault::Signal: return "signal";
    case SafetyFault::SocketClosed: return "socket closed";
    case SafetyFault::Stop: return "stop";
  }
  return "?";
}

namespace {
std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}
}  // namespace

bool isTransient(SafetyFault f) {
  return f == SafetyFault::CorruptPacket || f == SafetyFault::StaleSensors || f == SafetyFault::Fall ||
         f == SafetyFault::BadRequest;
}

Safety::Safety(const Params& params, Log log) : params_(params), log_(std::move(log)) {
  if (!log_) log_ = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
}

void Safety::sensorsOk(const JointArray& measured) {
  lastMeasured_ = measured;
  measured_ = true;
  if (!rampFromSet_) {
    rampFrom_ = measured;
    rampFromSet_ = true;
  }
  if (!isTransient(fault_)) return;
  if (++goodCycles_ * params_.cycleTime + 1e-9 >= params_.recoverTime) {
    log_("safety: resuming after " + std::string(safetyFaultName(fault_)) + "; stiffness ramps up over " +
         seconds(params_.rampTime));
    fault_ = SafetyFault::None;
    reason_.clear();
    lastLogged_.clear();
    startRamp();
  }
}

void Safety::fault(SafetyFault kind, const std::string& reason) {
  if (kind == SafetyFault::None) return;
  goodCycles_ = 0;
  // A final fault is never replaced by a transient one: the program is stopping.
  if (soft() && !isTransient(fault_) && isTransient(kind)) return;
  const bool wasSoft = soft();
  fault_ = kind;
  reason_ = reason;
  limit_ = 0;
  const std::string line = std::string("safety: ") + (wasSoft ? "still soft: " : "going soft in place: ") + reason;
  if (reason != lastLogged_) log_(line);
  lastLogged_ = reason;
}

void Safety::resume(const std::string& why) {
  if (fault_ != SafetyFault::User) return;
  log_("safety: resuming (" + why + "); stiffness ramps up over " + seconds(params_.rampTime));
  fault_ = SafetyFault::None;
  reason_.clear();
  lastLogged_.clear();
  startRamp();
}

void Safety::startRamp() {
  limit_ = 0;
  rampFrom_ = lastMeasured_;
  rampFromSet_ = measured_;
}

JointRequest Safety::softInPlace() const {
  JointRequest r;
  r.position = lastMeasured_;
  r.stiffness.fill(0);
  return r;
}

JointRequest Safety::apply(const JointRequest& requested) {
  if (soft() || !measured_) return softInPlace();
  // The limit of this cycle: 0 on the first answer, then one step per cycle.
  const double alpha = limit_;
  JointRequest out;
  for (int j = 0; j < NumJoints; ++j) {
    const double s = std::isfinite(requested.stiffness[j]) ? std::clamp(requested.stiffness[j], 0.0, 1.0) : 0.0;
    out.stiffness[j] = std::min(s, alpha);
    out.position[j] = alpha >= 1 ? requested.position[j] : rampFrom_[j] + alpha * (requested.position[j] - rampFrom_[j]);
  }
  const double step = params_.rampTime > 0 ? params_.cycleTime / params_.rampTime : 1.0;
  limit_ = std::min(1.0, limit_ + step);
  return out;
}

}  // namespace nao
