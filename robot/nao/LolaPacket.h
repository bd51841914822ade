#pragma once
// LoLA's msgpack packets (NAO V6), see ../shared/reference/nao-v6.md:
// the robot sends one sensor map every 12 ms, the client answers each with one actuator map.
// Arrays of 25 are in LoLA joint order (robot/JointIds.h). msgpack stays inside the .cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "robot/JointIds.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao::lola {

inline constexpr std::size_t kSensorPacketSize = 896;  // what LoLA sends (bytes)
inline constexpr std::size_t kMaxPacketSize = 8192;    // more without a complete map: corrupt stream

// Everything a sensor packet carries, as LoLA orders it.
struct SensorPacket {
  JointArray position{}, stiffness{}, current{}, temperature{}, status{};
  std::array<double, 3> accelerometer{};  // m/s^2
  std::array<double, 3> gyroscope{};      // rad/s
  std::array<double, 2> angles{};         // torso roll, pitch (rad)
  std::array<double, 4> battery{};        // charge, status (0x80 = charging), current, temperature
  std::array<double, NumFsr> fsr{};       // kg
  std::array<double, NumTouch> touch{};
  std::array<double, 2> sonar{};          // m
  std::array<std::string, 4> robotConfig;  // body id, body version, head id, head version
};

// The sensor map keys, in the order the documentation lists them; all are required.
inline constexpr std::array<const char*, 13> kSensorKeys = {
    "Position", "Stiffness", "Current", "Temperature", "Status", "Accelerometer", "Gyroscope",
    "Angles",   "Battery",   "FSR",     "Touch",       "Sonar",  "RobotConfig"};

// The actuator map.
struct ActuatorPacket {
  JointArray position{};   // rad
  JointArray stiffness{};  // 0..1
  LedRequest leds;
  std::array<bool, 2> sonar{true, true};
};

inline constexpr std::array<const char*, 11> kActuatorKeys = {
    "Position", "Stiffness", "Chest", "LEar", "REar", "LEye", "REye", "LFoot", "RFoot", "Skull", "Sonar"};

// Decodes exactly one msgpack map (no trailing bytes). Throws nao::Error("LoLA sensor packet",
// "<key>: <problem>") for bad msgpack, a missing key, a wrong type or array length, or a
// non-finite number; never reads past size, never allocates more than a few KiB.
SensorPacket decodeSensorPacket(const std::uint8_t* data, std::size_t size);

// The length of the first complete msgpack object in a stream buffer, 0 when more bytes are
// needed. Throws nao::Error when the bytes can never start a valid object.
std::size_t objectLength(const std::uint8_t* data, std::size_t size);

// Encodes the actuator map (floats as float32, LEDs clamped to 0..1, non-finite as 0).
std::vector<std::uint8_t> encodeActuatorPacket(const ActuatorPacket& packet);

// The sensor frame the robot program sees (time and cycle are the caller's).
void toSensorFrame(const SensorPacket& packet, SensorFrame& frame);
RobotInfo toRobotInfo(const SensorPacket& packet);

}  // namespace nao::lola
