#pragma once
// The seam between the robot program and the hardware. The same program runs against
// SimBackend (MuJoCo + OSMesa) and NaoBackend (LoLA socket + V4L2); nothing else differs.
//
// One cycle (12 ms, LoLA's rate):
//   backend.waitForSensors(frame)   // blocks until the next sensor frame
//   backend.takeImage(cam, image)   // true when a new image arrived since the last cycle
//   ... the program computes ...
//   backend.sendRequest(request)    // must answer within the cycle
#include <optional>
#include <string>

#include "robot/CameraImage.h"
#include "robot/ExposureWeights.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  virtual RobotInfo robotInfo() const = 0;
  // Returns false when the backend is gone (socket closed, simulation ended); reason says why.
  virtual bool waitForSensors(SensorFrame& frame) = 0;
  virtual bool takeImage(CameraId camera, CameraImage& image) = 0;
  virtual void sendRequest(const JointRequest& joints, const LedRequest& leds) = 0;
  // The camera's auto exposure meters with these weights from one of its next images on (the
  // robot program sends them when they change; a camera without them ignores them).
  virtual void setExposureWeights(CameraId /*camera*/, const ExposureWeights& /*weights*/) {}
  virtual std::string stopReason() const { return {}; }
};

inline constexpr double kCycleTime = 0.012;  // s, LoLA's 83.3 Hz
inline constexpr double kCameraPeriod = 1.0 / 30.0;

}  // namespace nao
