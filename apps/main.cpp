// nao-soccer: one command for the simulator, the evaluations and the robot program.
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "apps/Commands.h"
#include "robot/Error.h"

namespace {

struct Subcommand {
  const char* name;
  const char* summary;
  std::function<int(const nao::cli::Argv&)> run;
};

const std::vector<Subcommand>& subcommands() {
  static const std::vector<Subcommand> list = {
      {"render", "render a simulated camera image (or --view field for a top-down view)", nao::cli::renderCommand},
      {"run", "run the robot program on a backend (sim or nao)", nao::cli::runCommand},
      {"bench", "speed figures as JSON (sim, perception)", nao::cli::benchCommand},
      {"perceive", "the vision pipeline on a PNG/JPEG/raw YUV422 image: JSON and an annotated PNG", nao::cli::perceiveCommand},
      {"eval", "accuracy against ground truth over random cases (perception, calibration)", nao::cli::evalCommand},
      {"walk", "walk in the simulator (a speed, or --to a target): distance, speed, falls, odometry error", nao::cli::walkCommand},
      {"kick", "kick the ball in the simulator (--trials N): ball travel, direction error, falls", nao::cli::kickCommand},
      {"train", "train the ball classifier from simulated images (train ball)", nao::cli::trainCommand},
      {"calibrate", "calibrate the six camera offsets at the goal box (sim): true vs estimated", nao::cli::calibrateCommand},
  };
  return list;
}

void printHelp(std::FILE* out) {
  std::fprintf(out, "usage: nao-soccer <command> [options]   (nao-soccer <command> --help for its options)\n\ncommands:\n");
  for (const auto& c : subcommands()) std::fprintf(out, "  %-22s %s\n", c.name, c.summary);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    printHelp(stderr);
    return 2;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    printHelp(stdout);
    return 0;
  }
  const nao::cli::Argv args(argv + 2, argv + argc);
  for (const auto& c : subcommands()) {
    if (name != c.name) continue;
    try {
      return c.run(args);
    } catch (const nao::Error& e) {
      std::fprintf(stderr, "nao-soccer %s: %s\n", c.name, e.what());
      return 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "nao-soccer %s: internal error: %s\n", c.name, e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "nao-soccer: unknown command '%s' (nao-soccer --help lists them)\n", name.c_str());
  return 2;
}
