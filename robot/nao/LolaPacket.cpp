#include "robot/nao/LolaPacket.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <msgpack.hpp>

#include "robot/Error.h"

namespace nao::lola {
namespace {

const char* const kWhere = "LoLA sensor packet";

// Bounds that no valid packet comes near: a corrupt length field then fails at once instead of
// asking for gigabytes (msgpack checks these before it allocates).
msgpack::unpack_limit packetLimits() {
  return msgpack::unpack_limit(/*array*/ 64, /*map*/ 64, /*str*/ 256, /*bin*/ 256, /*ext*/ 256, /*depth*/ 4);
}

const char* typeName(msgpack::type::object_type t) {
  switch (t) {
    case msgpack::type::NIL: return "nil";
    case msgpack::type::BOOLEAN: return "a boolean";
    case msgpack::type::POSITIVE_INTEGER:
    case msgpack::type::NEGATIVE_INTEGER: return "an integer";
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64: return "a float";
    case msgpack::type::STR: return "a string";
    case msgpack::type::BIN: return "binary data";
    case msgpack::type::ARRAY: return "an array";
    case msgpack::type::MAP: return "a map";
    case msgpack::type::EXT: return "an extension object";
  }
  return "an unknown type";
}

std::string describe(const msgpack::object& o) {
  if (o.type == msgpack::type::ARRAY) return "an array of " + std::to_string(o.via.array.size);
  return typeName(o.type);
}

double number(const msgpack::object& o, const std::string& key, std::size_t index) {
  double v = 0;
  switch (o.type) {
    case msgpack::type::POSITIVE_INTEGER: v = static_cast<double>(o.via.u64); break;
    case msgpack::type::NEGATIVE_INTEGER: v = static_cast<double>(o.via.i64); break;
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64: v = o.via.f64; break;
    default:
      throw Error(kWhere, key + "[" + std::to_string(index) + "]: expected a number, got " + typeName(o.type));
  }
  if (!std::isfinite(v)) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    throw Error(kWhere, key + "[" + std::to_string(index) + "]: not a finite number (" + text + ")");
  }
  return v;
}

template <std::size_t N>
void numbers(const msgpack::object& o, const std::string& key, std::array<double, N>& out) {
  if (o.type != msgpack::type::ARRAY || o.via.array.size != N)
    throw Error(kWhere, key + ": expected an array of " + std::to_string(N) + " numbers, got " + describe(o));
  for (std::size_t i = 0; i < N; ++i) out[i] = number(o.via.array.ptr[i], key, i);
}

template <std::size_t N>
void strings(const msgpack::object& o, const std::string& key, std::array<std::string, N>& out) {
  if (o.type != msgpack::type::ARRAY || o.via.array.size != N)
    throw Error(kWhere, key + ": expected an array of " + std::to_string(N) + " strings, got " + describe(o));
  for (std::size_t i = 0; i < N; ++i) {
    const msgpack::object& s = o.via.array.ptr[i];
    if (s.type != msgpack::type::STR)
      throw Error(kWhere, key + "[" + std::to_string(i) + "]: expected a string, got " + typeName(s.type));
    out[i].assign(s.via.str.ptr, s.via.str.size);
  }
}

template <class Packer>
void packKey(Packer& pk, const char* key) {
  const std::size_t n = std::char_traits<char>::length(key);
  pk.pack_str(static_cast<std::uint32_t>(n));
  pk.pack_str_body(key, static_cast<std::uint32_t>(n));
}

// Always float32 (0xca): msgpack-c's pack_float writes whole numbers as integers, and LoLA
// wants floats.
void packFloat32(msgpack::sbuffer& buffer, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  const char bytes[5] = {static_cast<char>(0xca), static_cast<char>(bits >> 24), static_cast<char>(bits >> 16),
                         static_cast<char>(bits >> 8), static_cast<char>(bits)};
  buffer.write(bytes, 5);
}

template <class Packer, std::size_t N>
void packFloats(Packer& pk, msgpack::sbuffer& buffer, const char* key, const std::array<double, N>& values, bool unit) {
  packKey(pk, key);
  pk.pack_array(static_cast<std::uint32_t>(N));
  for (double v : values) {
    if (unit) v = std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0;
    packFloat32(buffer, static_cast<float>(v));
  }
}

}  // namespace

std::size_t objectLength(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::size_t offset = 0;
  try {
    msgpack::object_handle oh =
        msgpack::unpack(reinterpret_cast<const char*>(data), size, offset, nullptr, nullptr, packetLimits());
  } catch (const msgpack::insufficient_bytes&) {
    if (size > kMaxPacketSize)
      throw Error(kWhere, "no complete msgpack map in " + std::to_string(size) + " bytes");
    return 0;
  } catch (const std::exception& e) {
    throw Error(kWhere, std::string("not valid msgpack (") + e.what() + ")");
  }
  return offset;
}

SensorPacket decodeSensorPacket(const std::uint8_t* data, std::size_t size) {
  if (size == 0) throw Error(kWhere, "empty");
  msgpack::object_handle oh;
  std::size_t offset = 0;
  try {
    oh = msgpack::unpack(reinterpret_cast<const char*>(data), size, offset, nullptr, nullptr, packetLimits());
  } catch (const msgpack::insufficient_bytes&) {
    throw Error(kWhere, "truncated after " + std::to_string(size) + " bytes");
  } catch (const std::exception& e) {
    throw Error(kWhere, std::string("not valid msgpack (") + e.what() + ")");
  }
  if (offset != size)
    throw Error(kWhere, std::to_string(size - offset) + " bytes after the map");
  const msgpack::object& root = oh.get();
  if (root.type != msgpack::type::MAP) throw Error(kWhere, "expected a map, got " + describe(root));

  SensorPacket p;
  std::array<bool, kSensorKeys.size()> seen{};
  for (std::uint32_t i = 0; i < root.via.map.size; ++i) {
    const msgpack::object& k = root.via.map.ptr[i].key;
    const msgpack::object& v = root.via.map.ptr[i].val;
    if (k.type != msgpack::type::STR)
      throw Error(kWhere, "key #" + std::to_string(i) + ": expected a string, got " + typeName(k.type));
    const std::string key(k.via.str.ptr, k.via.str.size);
    const auto it = std::find_if(kSensorKeys.begin(), kSensorKeys.end(), [&](const char* s) { return key == s; });
    if (it == kSensorKeys.end()) continue;  // newer LoLA versions may add keys
    const auto index = static_cast<std::size_t>(it - kSensorKeys.begin());
    if (seen[index]) throw Error(kWhere, key + ": appears twice");
    seen[index] = true;
    switch (index) {
      case 0: numbers(v, key, p.position); break;
      case 1: numbers(v, key, p.stiffness); break;
      case 2: numbers(v, key, p.current); break;
      case 3: numbers(v, key, p.temperature); break;
      case 4: numbers(v, key, p.status); break;
      case 5: numbers(v, key, p.accelerometer); break;
      case 6: numbers(v, key, p.gyroscope); break;
      case 7: numbers(v, key, p.angles); break;
      case 8: numbers(v, key, p.battery); break;
      case 9: numbers(v, key, p.fsr); break;
      case 10: numbers(v, key, p.touch); break;
      case 11: numbers(v, key, p.sonar); break;
      case 12: strings(v, key, p.robotConfig); break;
    }
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    if (!seen[i]) throw Error(kWhere, std::string(kSensorKeys[i]) + ": missing");
  return p;
}

std::vector<std::uint8_t> encodeActuatorPacket(const ActuatorPacket& a) {
  msgpack::sbuffer buffer(1024);
  msgpack::packer<msgpack::sbuffer> pk(buffer);
  pk.pack_map(static_cast<std::uint32_t>(kActuatorKeys.size()));
  packFloats(pk, buffer, "Position", a.position, false);
  packFloats(pk, buffer, "Stiffness", a.stiffness, true);
  packFloats(pk, buffer, "Chest", a.leds.chest, true);
  packFloats(pk, buffer, "LEar", a.leds.leftEar, true);
  packFloats(pk, buffer, "REar", a.leds.rightEar, true);
  packFloats(pk, buffer, "LEye", a.leds.leftEye, true);
  packFloats(pk, buffer, "REye", a.leds.rightEye, true);
  packFloats(pk, buffer, "LFoot", a.leds.leftFoot, true);
  packFloats(pk, buffer, "RFoot", a.leds.rightFoot, true);
  packFloats(pk, buffer, "Skull", a.leds.skull, true);
  packKey(pk, "Sonar");
  pk.pack_array(2);
  for (bool b : a.sonar) b ? pk.pack_true() : pk.pack_false();
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(buffer.data());
  return {bytes, bytes + buffer.size()};
}

void toSensorFrame(const SensorPacket& p, SensorFrame& f) {
  f.joints.position = p.position;
  f.joints.stiffness = p.stiffness;
  f.joints.current = p.current;
  f.joints.temperature = p.temperature;
  f.inertial.accelerometer = Eigen::Vector3d(p.accelerometer[0], p.accelerometer[1], p.accelerometer[2]);
  f.inertial.gyroscope = Eigen::Vector3d(p.gyroscope[0], p.gyroscope[1], p.gyroscope[2]);
  f.inertial.angle = Eigen::Vector2d(p.angles[0], p.angles[1]);
  f.fsr.weight = p.fsr;
  f.touch = p.touch;
  f.sonar = p.sonar;
  f.battery.charge = p.battery[0];
  f.battery.status = p.battery[1];
  f.battery.current = p.battery[2];
  f.battery.temperature = p.battery[3];
}

RobotInfo toRobotInfo(const SensorPacket& p) {
  RobotInfo info;
  info.bodyId = p.robotConfig[0];
  info.bodyVersion = p.robotConfig[1];
  info.headId = p.robotConfig[2];
  info.headVersion = p.robotConfig[3];
  return info;
}

}  // namespace nao::lola
