// LoLA packets and the safety layer. The whole backend end to end is lola_peer_test
// (tests/lola_peer.cpp: a separate process speaking LoLA's documented msgpack over a real Unix
// socket to the real `nao-soccer run --backend nao --cameras none`).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include <msgpack.hpp>

#include "robot/Error.h"
#include "robot/nao/LolaPacket.h"
#include "robot/nao/Safety.h"

namespace nao {
namespace {

using Packer = msgpack::packer<msgpack::sbuffer>;

void key(Packer& pk, const std::string& k) { pk.pack(k); }
void floats(Packer& pk, const std::string& k, std::size_t n, double first, double step = 0.01) {
  key(pk, k);
  pk.pack_array(static_cast<uint32_t>(n));
  for (std::size_t i = 0; i < n; ++i) pk.pack_float(static_cast<float>(first + step * static_cast<double>(i)));
}

// A sensor map as LoLA sends it, built here with msgpack directly. `skip`: a key to leave
// out; `edit`: replaces one key's value.
std::vector<std::uint8_t> sensorPacket(const std::string& skip = "",
                                       const std::string& editKey = "",
                                       const std::function<void(Packer&)>& edit = {},
                                       bool extraKey = false) {
  msgpack::sbuffer buffer;
  Packer pk(buffer);
  const std::vector<std::pair<std::string, std::size_t>> keys = {
      {"Position", 25}, {"Stiffness", 25}, {"Current", 25}, {"Temperature", 25}, {"Status", 25},
      {"Accelerometer", 3}, {"Gyroscope", 3}, {"Angles", 2}, {"Battery", 4}, {"FSR", 8},
      {"Touch", 14}, {"Sonar", 2}, {"RobotConfig", 4}};
  pk.pack_map(static_cast<uint32_t>(keys.size() - (skip.empty() ? 0 : 1) + (extraKey ? 1 : 0)));
  if (extraKey) {
    key(pk, "SomethingNew");
    pk.pack_array(1);
    pk.pack(1);
  }
  double base = 0;
  for (const auto& [k, n] : keys) {
    base += 1;
    if (k == skip) continue;
    if (k == editKey) {
      key(pk, k);
      edit(pk);
      continue;
    }
    if (k == "Status") {
      key(pk, k);
      pk.pack_array(25);
      for (int i = 0; i < 25; ++i) pk.pack(i % 3);
    } else if (k == "RobotConfig") {
      key(pk, k);
      pk.pack_array(4);
      for (const char* s : {"BODY-ID", "6.0.0", "HEAD-ID", "6.0.1"}) pk.pack(std::string(s));
    } else {
      floats(pk, k, n, base);
    }
  }
  const auto* p = reinterpret_cast<const std::uint8_t*>(buffer.data());
  return {p, p + buffer.size()};
}

std::string decodeError(const std::vector<std::uint8_t>& bytes) {
  try {
    lola::decodeSensorPacket(bytes.data(), bytes.size());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LolaPacket, DecodesEveryDocumentedKeyInOrder) {
  const auto bytes = sensorPacket();
  const lola::SensorPacket p = lola::decodeSensorPacket(bytes.data(), bytes.size());
  EXPECT_NEAR(p.position[HeadYaw], 1.0, 1e-6);
  EXPECT_NEAR(p.position[RHand], 1.24, 1e-6);
  EXPECT_NEAR(p.stiffness[LKneePitch], 2.10, 1e-6);
  EXPECT_NEAR(p.current[0], 3.0, 1e-6);
  EXPECT_NEAR(p.temperature[24], 4.24, 1e-5);
  EXPECT_EQ(p.status[4], 1);
  EXPECT_NEAR(p.accelerometer[2], 6.02, 1e-6);
  EXPECT_NEAR(p.gyroscope[1], 7.01, 1e-6);
  EXPECT_NEAR(p.angles[1], 8.01, 1e-6);
  EXPECT_NEAR(p.battery[3], 9.03, 1e-6);
  EXPECT_NEAR(p.fsr[RFsrRR], 10.07, 1e-5);
  EXPECT_NEAR(p.touch[HeadRear], 11.03, 1e-5);
  EXPECT_NEAR(p.sonar[1], 12.01, 1e-5);
  EXPECT_EQ(p.robotConfig[2], "HEAD-ID");

  SensorFrame f;
  lola::toSensorFrame(p, f);
  EXPECT_NEAR(f.battery.charge, 9.0, 1e-6);  // Battery: charge, status, current, temperature
  EXPECT_NEAR(f.battery.status, 9.01, 1e-6);
  EXPECT_NEAR(f.battery.current, 9.02, 1e-6);
  EXPECT_NEAR(f.battery.temperature, 9.03, 1e-6);
  EXPECT_NEAR(f.inertial.angle.y(), 8.01, 1e-6);
  EXPECT_NEAR(f.joints.position[LHipYawPitch], 1.07, 1e-6);
  const RobotInfo info = lola::toRobotInfo(p);
  EXPECT_EQ(info.bodyId, "BODY-ID");
  EXPECT_EQ(info.headVersion, "6.0.1");
}

TEST(LolaPacket, IgnoresUnknownKeys) {
  const auto bytes = sensorPacket("", "", {}, true);
  EXPECT_NO_THROW(lola::decodeSensorPacket(bytes.data(), bytes.size()));
}

TEST(LolaPacket, CorruptPacketsNameTheKey) {
  EXPECT_NE(decodeError(sensorPacket("Touch")).find("Touch: missing"), std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "Position", [](Packer& pk) {
              pk.pack_array(24);
              for (int i = 0; i < 24; ++i) pk.pack(0.0);
            })).find("Position: expected an array of 25 numbers, got an array of 24"),
            std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "Gyroscope", [](Packer& pk) {
              pk.pack_array(3);
              pk.pack(0.0);
              pk.pack(std::nan(""));
              pk.pack(0.0);
            })).find("Gyroscope[1]: not a finite number"),
            std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "Angles", [](Packer& pk) {
              pk.pack_array(2);
              pk.pack(0.0);
              pk.pack(INFINITY);
            })).find("Angles[1]: not a finite number (inf)"),
            std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "Accelerometer", [](Packer& pk) { pk.pack(std::string("x")); }))
                .find("Accelerometer: expected an array of 3 numbers, got a string"),
            std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "FSR", [](Packer& pk) {
              pk.pack_array(8);
              for (int i = 0; i < 8; ++i) pk.pack_nil();
            })).find("FSR[0]: expected a number, got nil"),
            std::string::npos);
  EXPECT_NE(decodeError(sensorPacket("", "RobotConfig", [](Packer& pk) {
              pk.pack_array(4);
              for (int i = 0; i < 4; ++i) pk.pack(i);
            })).find("RobotConfig[0]: expected a string, got an integer"),
            std::string::npos);
}

TEST(LolaPacket, MalformedBytesNeverCrash) {
  const std::vector<std::vector<std::uint8_t>> cases = {
      {},
      {0xc1},                                      // never-used byte
      {0x93, 0x01, 0x02, 0x03},                    // an array, not a map
      {0xdd, 0xff, 0xff, 0xff, 0xff},              // array32 of 4 G elements: refused before allocating
      {0xdf, 0xff, 0xff, 0xff, 0xff},              // map32 of 4 G pairs
      {0xdb, 0xff, 0xff, 0xff, 0xff, 'a'},         // str32 of 4 GiB
      {0x81, 0xa3, 'F', 'S', 'R'},                 // truncated
  };
  for (const auto& c : cases) EXPECT_FALSE(decodeError(c).empty());
  auto good = sensorPacket();
  good.push_back(0xc0);
  EXPECT_NE(decodeError(good).find("1 bytes after the map"), std::string::npos);
  // A repeated key.
  msgpack::sbuffer b;
  Packer pk(b);
  pk.pack_map(2);
  floats(pk, "Angles", 2, 0);
  floats(pk, "Angles", 2, 0);
  EXPECT_NE(decodeError({reinterpret_cast<const std::uint8_t*>(b.data()), reinterpret_cast<const std::uint8_t*>(b.data()) + b.size()})
                .find("Angles: appears twice"),
            std::string::npos);
}

TEST(LolaPacket, SplitsAByteStream) {
  auto a = sensorPacket();
  const std::size_t n = a.size();
  EXPECT_EQ(lola::objectLength(a.data(), n / 2), 0u);  // incomplete: wait
  auto two = a;
  two.insert(two.end(), a.begin(), a.end());
  EXPECT_EQ(lola::objectLength(two.data(), two.size()), n);
  const std::uint8_t bad[] = {0xc1, 0x00};
  EXPECT_THROW(lola::objectLength(bad, sizeof bad), Error);
  // A string header announcing more than a packet can hold: corrupt once enough bytes pile up.
  std::vector<std::uint8_t> huge = {0xdb, 0x00, 0x10, 0x00, 0x00};
  EXPECT_EQ(lola::objectLength(huge.data(), huge.size()), 0u);
  huge.resize(lola::kMaxPacketSize + 1, 'x');
  EXPECT_THROW(lola::objectLength(huge.data(), huge.size()), Error);
}

TEST(LolaPacket, ActuatorPacketHasTheDocumentedKeysAndLengths) {
  lola::ActuatorPacket a;
  for (int j = 0; j < NumJoints; ++j) {
    a.position[j] = 0.1 * j;
    a.stiffness[j] = j == 3 ? 1.7 : j == 4 ? std::nan("") : 0.5;
  }
  a.leds.chest = {1, 0, 0.5};
  a.leds.leftEye[23] = 2;  // clamped
  a.sonar = {true, false};
  const auto bytes = lola::encodeActuatorPacket(a);
  const auto oh = msgpack::unpack(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const msgpack::object& o = oh.get();
  ASSERT_EQ(o.type, msgpack::type::MAP);
  const std::map<std::string, std::size_t> expected = {{"Position", 25}, {"Stiffness", 25}, {"Chest", 3}, {"LEar", 10},
                                                       {"REar", 10},     {"LEye", 24},      {"REye", 24},  {"LFoot", 3},
                                                       {"RFoot", 3},     {"Skull", 12},     {"Sonar", 2}};
  ASSERT_EQ(o.via.map.size, expected.size());
  std::map<std::string, std::vector<msgpack::object>> got;
  for (uint32_t i = 0; i < o.via.map.size; ++i) {
    const auto& kv = o.via.map.ptr[i];
    ASSERT_EQ(kv.key.type, msgpack::type::STR);
    const std::string k(kv.key.via.str.ptr, kv.key.via.str.size);
    ASSERT_TRUE(expected.count(k)) << k;
    ASSERT_EQ(kv.val.type, msgpack::type::ARRAY) << k;
    EXPECT_EQ(kv.val.via.array.size, expected.at(k)) << k;
    got[k].assign(kv.val.via.array.ptr, kv.val.via.array.ptr + kv.val.via.array.size);
  }
  EXPECT_EQ(got["Position"][10].type, msgpack::type::FLOAT32);
  EXPECT_NEAR(got["Position"][10].via.f64, 1.0, 1e-6);
  EXPECT_EQ(got["Stiffness"][3].via.f64, 1.0);  // clamped
  EXPECT_EQ(got["Stiffness"][4].via.f64, 0.0);  // NaN: soft
  EXPECT_EQ(got["LEye"][23].via.f64, 1.0);
  EXPECT_EQ(got["Chest"][2].via.f64, 0.5);
  EXPECT_EQ(got["Sonar"][0].type, msgpack::type::BOOLEAN);
  EXPECT_TRUE(got["Sonar"][0].via.boolean);
  EXPECT_FALSE(got["Sonar"][1].via.boolean);
}

// ---- Safety -----------------------------------------------------------------------------

struct SafetyFixture : ::testing::Test {
  std::vector<std::string> log;
  Safety safety{SafetyParams{}, [this](const std::string& l) { log.push_back(l); }};
  JointArray measured{}, request{};
  void SetUp() override {
    for (int j = 0; j < NumJoints; ++j) {
      measured[j] = 0.02 * j;
      request[j] = 0.5;
    }
  }
  JointRequest req() const {
    JointRequest r;
    r.position = request;
    r.stiffness.fill(1.0);
    return r;
  }
  JointRequest cycle() {
    safety.sensorsOk(measured);
    return safety.apply(req());
  }
};

TEST_F(SafetyFixture, RampsUpFromSoftInPlace) {
  EXPECT_EQ(safety.apply(req()).stiffness[0], 0.0);  // nothing measured yet: soft
  const JointRequest first = cycle();
  for (int j = 0; j < NumJoints; ++j) {
    EXPECT_EQ(first.stiffness[j], 0.0);
    EXPECT_EQ(first.position[j], measured[j]);  // starts where the joints are
  }
  double previous = safety.stiffnessLimit();
  int cycles = 1;
  while (cycle().stiffness[0] < 1.0 && cycles < 200) {
    const double s = safety.stiffnessLimit();
    EXPECT_LE(s - previous, 0.012 + 1e-9);
    previous = s;
    ++cycles;
  }
  EXPECT_NEAR(cycles, 84, 1);  // 1 s at 12 ms
  EXPECT_EQ(cycle().position[5], 0.5);
}

TEST_F(SafetyFixture, TransientFaultGoesSoftInPlaceAndRecovers) {
  for (int i = 0; i < 100; ++i) cycle();
  measured[3] = 0.77;
  safety.sensorsOk(measured);
  safety.fault(SafetyFault::CorruptPacket, "corrupt LoLA packet: Position: missing");
  const JointRequest soft = safety.apply(req());
  for (int j = 0; j < NumJoints; ++j) {
    EXPECT_EQ(soft.stiffness[j], 0.0);
    EXPECT_EQ(soft.position[j], measured[j]);
  }
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0], "safety: going soft in place: corrupt LoLA packet: Position: missing");
  safety.fault(SafetyFault::CorruptPacket, "corrupt LoLA packet: Position: missing");
  EXPECT_EQ(log.size(), 1u);  // the same reason again: no new line
  int softCycles = 0;
  while (cycle().stiffness[0] == 0 && softCycles < 500) ++softCycles;
  EXPECT_NEAR(softCycles, 84, 2);  // recoverTime 1 s, then the ramp's first step
  EXPECT_FALSE(safety.soft());
  EXPECT_NE(log.back().find("resuming after corrupt packet"), std::string::npos);
}

TEST_F(SafetyFixture, FinalFaultsStay) {
  for (int i = 0; i < 100; ++i) cycle();
  safety.fault(SafetyFault::Signal, "SIGTERM received: stopping");
  safety.fault(SafetyFault::StaleSensors, "stale");  // does not replace the final one
  for (int i = 0; i < 300; ++i) EXPECT_EQ(cycle().stiffness[0], 0.0);
  EXPECT_EQ(safety.currentFault(), SafetyFault::Signal);
}

TEST_F(SafetyFixture, UserUnstiffenUntilResumed) {
  for (int i = 0; i < 100; ++i) cycle();
  safety.fault(SafetyFault::User, "head buttons held");
  for (int i = 0; i < 300; ++i) EXPECT_EQ(cycle().stiffness[0], 0.0);
  safety.resume("chest button");
  EXPECT_EQ(cycle().stiffness[0], 0.0);  // the ramp starts at 0
  EXPECT_NEAR(cycle().stiffness[0], 0.012, 1e-9);
}

}  // namespace
}  // namespace nao
