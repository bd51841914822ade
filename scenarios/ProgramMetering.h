#pragma once
// The exposure weights the robot program would choose for a view (AutoExposureWeighting over
// OwnBodyProvider, their functions with their parameter files), for the scenarios that render
// single views without running a program: eval perception, render, train-ball. Its camera is
// the one the vision is told (the model's, with the offsets it believes), as in the program.
#include <string>

#include "perception/CameraCalibration.h"
#include "perception/CameraModel.h"
#include "perception/ExposureWeighting.h"
#include "perception/OwnBody.h"
#include "robot/ExposureWeights.h"
#include "robot/SensorData.h"

namespace nao {

class ProgramMetering {
 public:
  // Reads configDir/parameters/{AutoExposureWeighting,OwnBodyProvider}.json (a bad file
  // throws, naming it); empty: the compiled-in defaults.
  explicit ProgramMetering(const std::string& configDir);
  // cm: the camera as the program computes it from these sensors and the offsets it believes
  // (`calibration`).
  ExposureWeights operator()(const CameraMatrix& cm, const SensorFrame& sensors,
                             const CameraCalibration& calibration) const;
  // A camera placed by hand (a recorded real image's twin): no body in view.
  ExposureWeights operator()(const CameraMatrix& cm) const { return exposureWeights(cm, OwnBody{}, weighting_); }

 private:
  ExposureWeightingParams weighting_;
  OwnBodyParams body_;
};

}  // namespace nao
