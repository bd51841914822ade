#pragma once
// What keeps a real NAO from hurting itself while the robot program runs on it.
//
// - At start (and after every recovery) the stiffness limit ramps from 0 to 1 over rampTime,
//   and the position targets blend from the measured angles to the requested ones: nothing
//   jumps.
// - On a fault the joints go soft in place: stiffness 0, position = the last measured angles.
//   The reason is logged once (one line). Transient faults (a corrupt packet, a stale sensor
//   stream, a fall, a non-finite request) clear after recoverTime of good cycles, then the
//   ramp runs again; the others stay until the end (a signal, a closed socket, a stop) or
//   until resume() (the user's unstiffen).
#include <functional>
#include <string>

#include "robot/JointRequest.h"

namespace nao {

enum class SafetyFault { None, CorruptPacket, StaleSensors, Fall, BadRequest, User, Signal, SocketClosed, Stop };
const char* safetyFaultName(SafetyFault f);
// True for the faults that clear by themselves.
bool isTransient(SafetyFault f);

struct SafetyParams {
  double rampTime = 1.0;     // s for the stiffness limit to go from 0 to 1
  double recoverTime = 1.0;  // s of good cycles after a transient fault before the ramp restarts
  double cycleTime = 0.012;  // s per sensor packet
};

class Safety {
 public:
  using Params = SafetyParams;
  using Log = std::function<void(const std::string&)>;

  explicit Safety(const Params& params = {}, Log log = {});

  // Every valid sensor packet: remembers the measured angles and counts towards recovery.
  void sensorsOk(const JointArray& measured);
  // Goes (or stays) soft in place and logs why when the reason is new.
  void fault(SafetyFault kind, const std::string& reason);
  // Clears a User fault; the ramp starts again.
  void resume(const std::string& why);
  // The ramp (not yet run) starts from the angles measured last: while nothing was sent but
  // soft answers, the limp joints may have moved.
  void restartRamp() { startRamp(); }

  // What to send for the program's request this cycle (advances the ramp one cycle).
  JointRequest apply(const JointRequest& requested);
  // Stiffness 0, positions the last measured ones.
  JointRequest softInPlace() const;

  bool soft() const { return fault_ != SafetyFault::None; }
  SafetyFault currentFault() const { return fault_; }
  const std::string& reason() const { return reason_; }
  double stiffnessLimit() const { return limit_; }
  bool hasMeasurement() const { return measured_; }
  const JointArray& lastMeasured() const { return lastMeasured_; }

 private:
  void startRamp();

  Params params_;
  Log log_;
  SafetyFault fault_ = SafetyFault::None;
  std::string reason_, lastLogged_;
  int goodCycles_ = 0;
  double limit_ = 0;  // 0..1, caps the requested stiffness
  bool measured_ = false;
  JointArray lastMeasured_{};
  JointArray rampFrom_{};  // measured angles when the ramp started
  bool rampFromSet_ = false;
};

}  // namespace nao
