#pragma once
// The vision of one camera as a pipeline of modules, run once per image (B-Human's Upper and
// Lower threads, HULKs' Top and Bottom cyclers): the same modules for the top and the bottom
// camera, each camera with its own instance, blackboard and pipeline. Inputs: the image, the
// camera matrix and the robot's own body (OwnBody) at its exposure time and the painted sizes
// from the field file (VisionGeometry); output: one CameraPercepts per image. Which module provides which
// representation comes from config/camera_modules.json (a provider can be swapped there or
// through CameraPipelineConfig::providers, e.g. an oracle); the order follows from the
// modules' declarations.
//
//   CameraPipeline top(CameraId::Top, field);      // field: FieldDimensions
//   const CameraPercepts& p = top.process(image, cameraMatrix);
//   top.get<ScanLineRegions>();                    // an intermediate result, for drawing
//
// runVision (VisionPipeline.h), `eval perception` and `bench perception` run through this.
#include <any>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "perception/CameraModel.h"
#include "perception/FieldDimensions.h"
#include "perception/OwnBody.h"
#include "perception/vision/VisionPipeline.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/Blackboard.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/ModuleRegistry.h"

namespace nao {

struct CameraPipelineConfig {
  std::string configDir;  // holds camera_modules.json and parameters/; empty: the installed config/
  std::string headId;     // per-robot parameter overlay; empty: none
  ProviderMap providers;  // representation -> module, replacing config/camera_modules.json's choice
  std::map<std::string, std::any> params;  // module -> its Params instead of its file (ModuleContext::params)
  DebugChannels* debug = nullptr;  // for the modules and `timing` (as "vision_top"/"vision_bottom"); not owned
};

class CameraPipeline {
 public:
  // Throws nao::Error for a bad config/camera_modules.json or a pipeline that cannot be ordered.
  CameraPipeline(CameraId camera, const FieldDimensions& field, const CameraPipelineConfig& config = {});
  CameraPipeline(CameraId camera, const VisionGeometry& geometry, const CameraPipelineConfig& config = {});

  // Runs every module on this image (taken with the camera matrix `cm`, calibrated, at its
  // exposure time; `body`: the robot's own body then, none by default). An invalid image (no
  // pixels) gives percepts with nothing seen. An image of the other camera is a nao::Error.
  const CameraPercepts& process(const CameraImage& image, const CameraMatrix& cm, const OwnBody& body = {});
  const CameraPercepts& percepts() const { return percepts_; }

  // Any representation on this pipeline's board after process (ScanGrid, ScanLineRegions,
  // FieldBoundary, LineSpots, ...), e.g. for drawing.
  template <class T>
  const T& get() const {
    return board_.read<T>();
  }
  // The last image's results as runVision returned them (regions, boundary, obstacles, lines,
  // ball, stage times), for annotateVision and the older callers.
  VisionResult visionResult() const;

  struct ModuleTime {
    std::string module;
    double ms = 0;  // wall time of its update
  };
  // Per module of the last process, in pipeline order (empty for an invalid image), and the
  // whole process call (ms).
  const std::vector<ModuleTime>& moduleMs() const { return moduleMs_; }
  double totalMs() const { return totalMs_; }

  CameraId camera() const { return camera_; }
  const VisionGeometry& geometry() const { return geometry_; }
  std::vector<std::string> order() const { return pipeline_.order(); }
  // The default choice of providers: config/camera_modules.json in the installed config/.
  static std::string defaultProvidersFile();

 private:
  CameraId camera_;
  VisionGeometry geometry_;
  Blackboard board_;
  Pipeline pipeline_;
  CameraPercepts percepts_;
  std::vector<ModuleTime> moduleMs_;
  double totalMs_ = 0;
  bool processed_ = false;  // the board holds the modules' results of a valid image
  DebugChannels* debug_ = nullptr;
};

}  // namespace nao
