// Writes seed inputs for the fuzz targets: a valid LoLA sensor packet (built with msgpack as
// LoLA sends it) and damaged variants, valid GameController and return packets.
// usage: fuzz_seeds DIR   (writes DIR/lola/*, DIR/gamecontroller/* and DIR/calibration_log/*)
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <msgpack.hpp>

#include "perception/calibration/CalibrationLog.h"
#include "robot/nao/GameController.h"

namespace {

void write(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string sensorPacket(int variant) {
  msgpack::sbuffer b;
  msgpack::packer<msgpack::sbuffer> pk(b);
  const std::vector<std::pair<const char*, int>> keys = {
      {"Position", 25}, {"Stiffness", 25}, {"Current", 25}, {"Temperature", 25}, {"Status", 25},
      {"Accelerometer", 3}, {"Gyroscope", 3}, {"Angles", 2}, {"Battery", 4}, {"FSR", 8},
      {"Touch", 14}, {"Sonar", 2}, {"RobotConfig", 4}};
  pk.pack_map(static_cast<uint32_t>(keys.size()));
  for (const auto& [k, n] : keys) {
    pk.pack(std::string(k));
    pk.pack_array(static_cast<uint32_t>(variant == 1 && std::string(k) == "Position" ? n - 1 : n));
    for (int i = 0; i < (variant == 1 && std::string(k) == "Position" ? n - 1 : n); ++i) {
      if (std::string(k) == "RobotConfig") pk.pack(std::string("P0000074A04S8C700011"));
      else if (std::string(k) == "Status") pk.pack(i % 3);
      else pk.pack_double(variant == 2 && i == 1 ? 1e300 : 0.1 * i + 0.05);
    }
  }
  return std::string(b.data(), b.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  ::mkdir(dir.c_str(), 0755);
  ::mkdir((dir + "/lola").c_str(), 0755);
  ::mkdir((dir + "/gamecontroller").c_str(), 0755);
  for (int v = 0; v < 3; ++v) write(dir + "/lola/sensor" + std::to_string(v), sensorPacket(v));
  nao::gc::GameControlData d;
  d.state = nao::gc::State::Playing;
  d.teams[0].teamNumber = 12;
  d.teams[1].teamNumber = 34;
  d.teams[0].players[2].penalty = 2;
  const auto p = nao::gc::serialize(d);
  write(dir + "/gamecontroller/gc18", std::string(p.begin(), p.end()));
  nao::gc::ReturnData r;
  r.playerNum = 3;
  r.teamNum = 12;
  const auto q = nao::gc::serialize(r);
  write(dir + "/gamecontroller/return4", std::string(q.begin(), q.end()));
  // A calibration log of two small views.
  ::mkdir((dir + "/calibration_log").c_str(), 0755);
  nao::calibration::CalibrationLog log;
  log.headId = "P0000074A04S8C700011";
  log.backend = "nao";
  for (int v = 1; v <= 2; ++v) {
    nao::calibration::CalibrationLogRecord rec;
    rec.viewId = v;
    rec.image.camera = v == 1 ? nao::CameraId::Top : nao::CameraId::Bottom;
    rec.image.width = 4;
    rec.image.height = 2;
    rec.image.timestamp = 3.5 * v;
    rec.image.yuyv.assign(16, static_cast<std::uint8_t>(40 * v));
    rec.accepted = v == 1;
    log.records.push_back(rec);
  }
  write(dir + "/calibration_log/two_views", nao::calibration::serializeCalibrationLog(log));
  return 0;
}
