#pragma once
// The calibration log: every image the robot program's Calibrator judged during phase 1, with
// what it measured the image with (the joints and the torso's roll and pitch at the exposure),
// so that `calibrate --from-log` solves again without a simulator, from what a real NAO saw.
//
// A binary container: the magic line "NAOCALLOG\n", then chunks of
//   [u32 little-endian JSON length][JSON][u32 little-endian payload length][payload]
// The first chunk is the header ({"format": 1, "head_id": ..., "backend": ...}, no payload),
// each record's JSON holds the view, camera, time, size, joints, IMU angle and the live verdict
// with the image's YUYV bytes as its payload, and the last chunk is {"end": true, "records": N}:
// a log without it was cut short.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "robot/CameraImage.h"
#include "robot/JointIds.h"

namespace nao::calibration {

struct CalibrationLogRecord {
  int viewId = 0;          // the behaviour's view (CalibrationRequest::viewId)
  CameraImage image;       // its camera and exposure time included
  JointArray joints{};     // at the exposure (FrameHistory)
  Eigen::Vector2d imuAngle = Eigen::Vector2d::Zero();  // the torso's roll and pitch at the exposure, rad
  bool accepted = false;   // the live Calibrator's verdict ...
  std::string reason;      // ... and why not
};

struct CalibrationLog {
  std::string headId;   // the robot that recorded it (the calibration store's key)
  std::string backend;  // sim or nao
  std::vector<CalibrationLogRecord> records;
};

// The log as bytes.
std::string serializeCalibrationLog(const CalibrationLog& log);
// Throws nao::Error(source, ...) naming the record and what is wrong with it: not a log, a
// record cut short (truncated), a field missing or out of range, no end marker.
CalibrationLog parseCalibrationLog(std::string_view bytes, const std::string& source);
// Reads and parses a file; throws nao::Error(path, ...) when it cannot be read or parsed.
CalibrationLog readCalibrationLog(const std::string& path);

}  // namespace nao::calibration
