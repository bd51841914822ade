// nao-soccer run: the robot program on a backend.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/Commands.h"
#include "apps/RunNao.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "scenarios/SimRun.h"

namespace nao::cli {

int runCommand(const Argv& argv) {
  auto options = commonOptions();
  for (auto& o : simOptions()) options.push_back(o);
  for (auto& o : naoRunOptions()) options.push_back(o);
  options.insert(options.end(), {{"backend", "sim|nao", "where the robot program runs (default sim)"},
                                 {"seconds", "S", "how long to run (sim: default 10; nao: until stopped)"},
                                 {"pose", "X,Y,THETA", "sim: start pose m, m, deg (default: calibration position)"},
                                 {"cameras", "on|off|none|v4l2", "sim: on|off, render both cameras at 30 Hz (default on); nao: none|v4l2 (default v4l2)"},
                                 {"images", "DIR", "sim: write camera PNGs once a second and a field view"}});
  Args args("run", argv, options);
  if (args.helpRequested()) {
    std::cout << args.usage();
    return 0;
  }
  const std::string backend = args.str("backend", "sim");
  if (backend == "nao") return runNao(args);
  if (backend != "sim") throw Error("--backend", "must be sim or nao, not '" + backend + "'");

  sim::SimRunOptions o;
  o.field = fieldFrom(args);
  o.robotModel = robotModelFrom(args);
  o.seconds = args.num("seconds", 10);
  if (!(o.seconds > 0) || o.seconds > 36000) throw Error("--seconds", "must be in (0, 36000]");
  if (auto p = args.optionalList("pose", 3)) o.pose = Eigen::Vector3d((*p)[0], (*p)[1], (*p)[2] * M_PI / 180);
  else o.pose = Eigen::Vector3d(-(o.field.length / 2 - o.field.penaltyCrossDistance), -o.field.width / 2, M_PI / 2);
  const std::string cameras = args.str("cameras", "on");
  if (cameras != "on" && cameras != "off") throw Error("--cameras", "must be on or off");
  o.cameras = cameras == "on";
  o.lighting = lightingFrom(args);
  o.miscalibration = miscalibrationFrom(args, args.seed());
  o.imagesDir = args.str("images", "");
  o.seed = args.seed();
  o.progress = [&](double t) { progress("run: simulated seconds", static_cast<std::size_t>(t + 0.5), static_cast<std::size_t>(o.seconds + 0.5)); };

  const sim::SimRunResult r = sim::runSim(o);
  std::fprintf(stderr,
               "run: %.1f s simulated in %.1f s (%.2fx real time), %llu cycles, %d top + %d bottom images, "
               "torso height %.3f..%.3f m, %s\n",
               r.simSeconds, r.wallSeconds, r.simSeconds / std::max(r.wallSeconds, 1e-9),
               static_cast<unsigned long long>(r.cycles), r.imagesTop, r.imagesBottom, r.torsoHeightMin,
               r.torsoHeightMax, r.fell ? "FELL" : "no fall");
  // The JSON holds results only (no wall-clock figures: `bench sim` measures speed), so the
  // same --seed gives the same bytes.
  if (args.has("json")) {
    nlohmann::json j = {{"backend", backend},
                        {"sim_seconds", r.simSeconds},
                        {"cycles", r.cycles},
                        {"images", {{"top", r.imagesTop}, {"bottom", r.imagesBottom}}},
                        {"fell", r.fell},
                        {"torso_height_m", {{"min", r.torsoHeightMin}, {"max", r.torsoHeightMax}}},
                        {"final_pose", {r.finalPose.x(), r.finalPose.y(), r.finalPose.z() * 180 / M_PI}},
                        {"modules", r.moduleOrder},
                        {"files", r.imagesWritten},
                        {"miscalibration_deg", calibrationDegJson(o.miscalibration)},
                        {"lighting", lightingJson(o.lighting)},
                        {"seed", o.seed}};
    writeJson(args.str("json", "-"), j);
  }
  return r.fell ? 1 : 0;
}

}  // namespace nao::cli
