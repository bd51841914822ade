// Every nao-soccer command and its options: the one place that says what a command takes, in
// which unit and range, with which default. apps/main.cpp binds each command to its run function.
#include <arpa/inet.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include "apps/cli/CommandLine.h"
#include "apps/cli/Options.h"
#include "robot/Debug.h"
#include "robot/Error.h"
#include "robot/JointLimits.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"
#include "robot/nao/ImageFiles.h"
#include "robot/nao/GameController.h"

namespace nao::cli {

namespace {

using E = OptionSpec::Element;

const std::string kFieldFile = "config/field_dimensions.json";
// --venue: none, random, or a venue of config/venues.json (checked in full, against the run's
// field, when the run starts: scenarios/Venue.h).
std::string venueProblem(const std::string& value) {
  if (value == "none" || value == "random") return "";
  std::ifstream in(dataPath("config/venues.json"));
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  std::string names;
  if (!j.is_discarded() && j.contains("venues") && j["venues"].is_array())
    for (const auto& v : j["venues"])
      if (v.is_object() && v.contains("name") && v["name"].is_string()) {
        if (v["name"] == value) return "";
        names += (names.empty() ? "" : ", ") + v["name"].get<std::string>();
      }
  return "unknown venue '" + value + "' (none, random" + (names.empty() ? "" : ", " + names) + ")";
}
const std::string kVenueHelp =
    "none (phase 2's balls from the seed, the plain diagram), random (the trial seed's turn through config/venues.json) "
    "or a venue's name there: its taped balls, carpet friction and look";

const std::string kOpponentHelp =
    "the away robot: self (our robot program, as home), baseline (ours playing the scripted baseline: to the ball, "
    "kick at the goal) or DIR, a robot program configuration (modules.json, parameters/)";

const std::string kLightingHelp =
    "lighting: a preset (default, bright, dark, warm, cold, shadows, noisy, shadows-low-dim, dim) or a key=value list "
    "(intensity, temperature, shadows, elevation, azimuth, ambient, noise; the camera model's camera, ae, awb, "
    "vignetting, defocus, motion = on|off; config/lighting.json, config/camera_sensor.json)";

// A robot pose on the field; x and y are checked against the field file (with its border).
std::vector<E> poseElements() { return {{"X", "m", -20, 20}, {"Y", "m", -20, 20}, {"THETA_DEG", "deg", -360, 360}}; }
std::vector<E> headElements() {
  return {{"YAW", "deg", kJointLimitsDeg[HeadYaw].min, kJointLimitsDeg[HeadYaw].max},
          {"PITCH", "deg", kJointLimitsDeg[HeadPitch].min, kJointLimitsDeg[HeadPitch].max}};
}
std::vector<E> offsetElements() {
  std::vector<E> e;
  for (const char* n : {"B_ROLL", "B_PITCH", "T_ROLL", "T_PITCH", "B2_ROLL", "B2_PITCH"}) e.push_back({n, "deg", -20, 20});
  return e;
}

const std::string kVenueLookHelp =
    "how the venue looks: none (the plain diagram), random (the seed's turn through config/venues.json) or a venue's "
    "name there (its carpet, paint, hall, boards, tables and people)";

void simOptions(Command& c, SimOptions& s, bool miscalibration = true, bool venue = true) {
  c.text("--lighting", s.lighting, "SPEC", kLightingHelp + " (default " + s.lighting + ")");
  if (venue) c.text("--venue", s.venue, "NAME", kVenueLookHelp + " (default " + s.venue + ")", venueProblem);
  if (miscalibration)
    c.choiceOrNumbers("--miscalibration", s.miscalibration, s.miscalibrationDeg, {"none", "random"}, offsetElements(),
                      "injected camera offsets: none, random (+-3 deg each, from --seed) or body, top and bottom "
                      "roll and pitch");
  c.inputFile("--model", s.model, "the robot's MJCF (default models/nao_v6.xml)");
}

std::string ipv4Problem(const std::string& s) {
  in_addr a{};
  return ::inet_pton(AF_INET, s.c_str(), &a) == 1 ? "" : "'" + s + "' is not an IPv4 address";
}

// --seed, --json and --field (the standard field by default): what most commands take.
void seedJsonField(Command& c) {
  c.seed();
  c.json();
  c.field(kFieldFile);
}

// --seeds LIST of a resumable evaluation: exactly these seeds, instead of --seed and the count.
void seedsOption(Command& c, std::vector<std::uint64_t>& seeds, const std::string& countFlag) {
  c.seedList("--seeds", seeds, "run exactly these seeds (as batch's chunks do) instead of --seed and " + countFlag)
      ->excludes(c.app()->get_option("--seed"))
      ->excludes(c.app()->get_option(countFlag));
}

// What batch runs: `eval TARGET [options]` of an evaluation with rows, its options as valid as
// they would be alone; --rows is batch's. Throws nao::Error naming the word.
void checkBatchEval(const std::vector<std::string>& args) {
  if (args.empty()) throw Error("batch", "needs the evaluation to run: batch eval challenge|match|localization|calibration [its options]");
  if (args[0] != "eval") {
    if (args[0].size() > 1 && args[0][0] == '-')
      throw Error(args[0].substr(0, args[0].find('=')), "not an option of 'batch' (nao-soccer batch --help lists them)");
    throw Error(args[0], "unexpected argument for 'batch' (batch eval challenge|match|localization|calibration [its options])");
  }
  CommandLine inner;
  std::vector<const char*> argv{"nao-soccer"};
  for (const auto& a : args) argv.push_back(a.c_str());
  std::string help;
  const Command* c = inner.parse(static_cast<int>(argv.size()), argv.data(), help);
  if (!c) throw Error("--help", "batch runs an evaluation, it does not print its help (nao-soccer " + args[0] + " --help)");
  static const std::set<std::string> withRows = {"eval challenge", "eval match", "eval localization", "eval calibration"};
  if (!withRows.count(c->path()))
    throw Error(c->path(), "has no rows to split yet (batch runs eval challenge, eval match, eval localization and eval calibration)");
  for (const auto& a : args)
    if (a == "--rows" || a.rfind("--rows=", 0) == 0) throw Error("--rows", "batch keeps the rows itself: one file per chunk in --dir");
}

std::string pathProblem(const std::string& s) { return s.empty() ? "an empty path" : ""; }

// --debug and --debug-out (robot/Debug.h): the names are checked against the declared channels
// before the run.
void debugOptions(Command& c, DebugOptions& d) {
  // The help does not list the channels: each program (nao-soccer, nao-soccer-robot) declares its
  // own, and their `run --help` must read the same.
  auto* channels = c.text("--debug", d.channels, "CHANNEL[,CHANNEL]",
                          "write these debug channels as JSON lines (`nao-soccer modules` lists them and what "
                          "each holds; an unknown name is refused with the list)",
                          debugChannelsProblem);
  c.outputFile("--debug-out", d.out, "where --debug writes (default stderr)")->needs(channels);
}

// --cameras files:DIR: DIR/top/ and DIR/bottom/ each hold PNG or JPEG images; socket:PATH: a
// Unix socket path (it may appear later: the cameras wait for it).
const std::string kPerceptsHelp =
    "vision (both cameras rendered, the camera pipeline) or oracle (the fast percept mode: no rendering, percepts "
    "from the simulator's view with the vision's fitted errors, config/parameters/OracleVision.json)";

// --opponent's other value: a robot program configuration folder.
std::string opponentConfigProblem(const std::string& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return "neither self, baseline nor a configuration folder";
  if (!std::filesystem::is_regular_file(std::filesystem::path(dir) / "modules.json", ec))
    return dir + ": a configuration folder holds modules.json (and parameters/)";
  return "";
}

std::string cameraSourceProblem(const std::string& s) {
  if (s.rfind("socket:", 0) == 0) {
    const std::string path = s.substr(7);
    if (path.empty()) return "socket: needs a path";
    if (path.size() > 100) return "socket: a Unix socket path has at most 100 characters";
    return "";
  }
  const std::string prefix = "files:";
  if (s.rfind(prefix, 0) != 0) return "not a choice";
  const std::string dir = s.substr(prefix.size());
  if (dir.empty()) return "files: needs a folder";
  for (const char* camera : {"top", "bottom"})
    if (imageFilesIn(dir + "/" + camera).empty())
      return dir + "/" + camera + "/ holds no PNG or JPEG images";
  return "";
}

}  // namespace

void CommandLine::declare() {
  Options& o = *options_;
  CLI::App* root = root_.get();

  {
    RenderOptions& r = o.render;
    Command& c = leaf(root, "render", "one simulated camera image (or --view field: the field from above)", r.common);
    c.gl();
    seedJsonField(c);
    simOptions(c, r.sim);
    c.choice("--camera", r.camera, {"top", "bottom"}, "which camera");
    c.choice("--view", r.view, {"camera", "field"}, "a camera image or a top-down view of the field");
    c.numbers("--pose", r.pose, poseElements(), "the robot's pose on the field (default 0,0,0)");
    c.onField("--pose", r.pose);
    c.numbers("--head", r.head, headElements(), "head angles within the joints' limits (default 0,0)");
    c.numbers("--ball", r.ball, {{"X", "m", -20, 20}, {"Y", "m", -20, 20}}, "a ball on the field");
    c.onField("--ball", r.ball);
    c.inputFile("--camera-matrix", r.cameraMatrix,
                "the simulated twin of a real image: its recorded camera matrix and goal-box labels (the JSON of "
                "../shared/data/real-goalbox-images/README.md) place the camera where the robot stood beside the own "
                "goal box; replaces --pose, --head and --miscalibration");
    c.rule([&r] {
      for (const char* f : {"--pose", "--head", "--miscalibration", "--view"})
        if (!r.cameraMatrix.empty() && r.common.has(f))
          return std::string("--camera-matrix: places the camera itself; ") + f + " is not used with it";
      return std::string();
    });
    c.outputFile("--out", r.out, "where to write the PNG")->required();
  }
  {
    RunOptions& r = o.run;
    Command& c = leaf(root, "run", "the robot program on a backend: the simulator (sim) or a NAO (nao)", r.common);
    c.gl();
    c.choice("--backend", r.backend, {"sim", "nao"}, "where the robot program runs");
    seedJsonField(c);
    simOptions(c, r.sim);
    c.number("--seconds", r.seconds, 0.1, 86400, "s", "how long to run (nao: until stopped unless given; sim: at most 3600)");
    c.numbers("--pose", r.pose, poseElements(), "sim: the start pose (default: the calibration position)");
    c.onField("--pose", r.pose);
    c.numbers("--goto", r.goTo, poseElements(),
              "the behaviour walks to this field pose by the robot's own localization (default: it stands)");
    c.onField("--goto", r.goTo);
    c.numbers("--ball", r.ball, {{"X", "m", -20, 20}, {"Y", "m", -20, 20}}, "sim: a ball lying here (default: none)");
    c.onField("--ball", r.ball);
    c.choice("--cameras", r.cameras, {"on", "off", "none", "v4l2"},
             "sim: on|off, both cameras rendered at 30 Hz (default on); nao: none|v4l2|files:DIR|socket:PATH (default "
             "v4l2; files: the PNG/JPEG images of DIR/top/ and DIR/bottom/ in name order, looping, 30 Hz each; "
             "socket: frames a simulator sends over the Unix socket PATH, as tests/sim_lola_peer does)",
             "files:DIR|socket:PATH", cameraSourceProblem);
    c.outputFolder("--images", r.images, "sim: camera PNGs once a second and a field view into DIR");
    debugOptions(c, r.debug);
    NaoRunOptions& n = r.nao;
    c.text("--lola-socket", n.lolaSocket, "PATH", "nao: LoLA's Unix socket (default /tmp/robocup)", pathProblem);
    c.text("--camera-top", n.cameraTop, "DEV", "nao: top camera device (default /dev/video-top)", pathProblem);
    c.text("--camera-bottom", n.cameraBottom, "DEV", "nao: bottom camera device (default /dev/video-bottom)", pathProblem);
    c.inputFile("--camera-settings", n.cameraSettings, "nao: camera resolution, exposure, gain, white balance (JSON)");
    c.choice("--clock", n.clock, {"monotonic", "lola"},
             "nao: the program's clock: monotonic (as on a NAO) or lola, 12 ms per LoLA packet, for a simulator "
             "slower than real time (tests/sim_lola_peer; only with --cameras none or socket:PATH, or with --lockstep)");
    c.flag("--lockstep", n.lockstep,
           "nao: deterministic, for replaying recorded LoLA packets and images: the program is built before the first "
           "answer, cognition runs in the motion cycle, file frames are due on the LoLA clock and waited for, no "
           "stale-sensor timeout (needs --clock lola and --cameras none or files:DIR)");
    c.text("--speech-command", n.speechCommand, "CMD",
           "nao: the text-to-speech command, each utterance appended as its last argument (default 'flite -t', shipped "
           "in the bundle; 'none': the log only)",
           [](const std::string& s) {
             return s.find_first_not_of(" \t") == std::string::npos ? std::string("an empty command ('none' for none)")
                                                                      : std::string();
           });
    c.outputFile("--record", n.record,
                  "nao: write the calibration log when the run ends: each image the Calibrator judged, with its joints "
                  "and IMU angle (calibrate --from-log solves from it)");
    c.count("--team", n.team, 0, 254, "nao: team number for the GameController (0: none)");
    c.count("--player", n.player, 1, gc::kMaxPlayers, "nao: player number");
    c.count("--gc-port", n.gcPort, 1, 65535, "nao: GameController UDP port");
    c.count("--gc-return-port", n.gcReturnPort, 1, 65535, "nao: port of the return packets");
    c.text("--gc-address", n.gcAddress, "IP", "nao: address to receive GameController packets on (default 0.0.0.0)",
           ipv4Problem);
    c.onlyWith("--backend", "sim", r.backend,
               {"--seed", "--lighting", "--miscalibration", "--model", "--pose", "--images", "--ball"});
    c.onlyWith("--backend", "nao", r.backend,
               {"--lola-socket", "--camera-top", "--camera-bottom", "--camera-settings", "--team", "--player",
                "--gc-port", "--gc-return-port", "--gc-address", "--lockstep", "--speech-command", "--record"});
    c.rule([&r] {
      const bool simValue = r.cameras == "on" || r.cameras == "off";
      if (!r.cameras.empty() && simValue != (r.backend == "sim"))
        return "--cameras: " + r.cameras + " is not a choice with --backend " + r.backend +
               (r.backend == "sim" ? " (on or off)" : " (none, v4l2, files:DIR or socket:PATH)");
      if (r.nao.lockstep && (r.nao.clock != "lola" || !(r.cameras == "none" || r.cameras.rfind("files:", 0) == 0)))
        return std::string("--lockstep: only with --clock lola and --cameras none or files:DIR");
      if (r.nao.clock == "lola" && !r.nao.lockstep &&
          (r.backend != "nao" || !(r.cameras == "none" || r.cameras.rfind("socket:", 0) == 0)))
        return std::string("--clock lola: only with --backend nao and --cameras none or socket:PATH (its frames carry the "
                           "LoLA clock), or with --lockstep");
      if (r.backend == "sim" && r.seconds > 3600) return std::string("--seconds: at most 3600 with --backend sim");
      return std::string();
    });
  }
  {
    CLI::App* bench = group("bench", "speed figures as JSON: sim, program, match, perception, calibration");
    BenchSimOptions& s = o.benchSim;
    Command& c = leaf(bench, "sim", "physics and rendering speed: real-time factors, render ms per camera", s.common);
    c.gl();
    seedJsonField(c);
    c.text("--lighting", s.lighting, "SPEC", kLightingHelp + " (default " + s.lighting + ")");
    c.text("--venue", s.venue, "NAME", kVenueLookHelp + " (default " + s.venue + ")", venueProblem);
    c.inputFile("--model", s.model, "the robot's MJCF (default models/nao_v6.xml)");
    c.number("--seconds", s.seconds, 1, 600, "s", "simulated seconds per physics run (camera runs: at most 10)");
    c.count("--repeats", s.repeats, 1, 20, "runs per figure; the median is reported");
    c.flag("--profile", s.profile,
           "where the time goes: each camera image's stages (scene update, draw, read-back, the camera sensor's pass) and the "
           "camera runs' wall shares (render, cognition, motion, physics and the rest)");

    BenchProgramOptions& g = o.benchProgram;
    Command& cg = leaf(bench, "program",
                       "the robot program in the simulator, both cameras at 30 Hz: ms per cognition run and motion "
                       "cycle, real-time factor",
                       g.common);
    cg.gl();
    seedJsonField(cg);
    cg.text("--lighting", g.lighting, "SPEC", kLightingHelp + " (default " + g.lighting + ")");
    cg.inputFile("--model", g.model, "the robot's MJCF (default models/nao_v6.xml)");
    cg.number("--seconds", g.seconds, 1, 600, "s", "simulated seconds per run");
    cg.count("--repeats", g.repeats, 1, 20, "runs; the median of each figure over them is reported");
    cg.numbers("--goto", g.goTo, poseElements(),
               "the behaviour walks from the calibration position to this field pose (default 0,0,0: the centre)");
    cg.onField("--goto", g.goTo);
    cg.flag("--per-module", g.perModule,
            "one more run with the timing channel: each module's median ms (the channel's overhead included)");

    BenchMatchOptions& m = o.benchMatch;
    Command& cm = leaf(bench, "match",
                       "a 1vs1 game's speed, both robot programs with four cameras at 30 Hz: real-time factor with "
                       "the vision and with the fast percept mode, side by side, and where the wall time goes",
                       m.common);
    cm.gl();
    seedJsonField(cm);
    cm.text("--lighting", m.lighting, "SPEC", kLightingHelp + " (default " + m.lighting + ")");
    cm.number("--seconds", m.seconds, 1, 600, "s", "simulated seconds per game, from its start (the robots walk in during READY)");
    cm.count("--repeats", m.repeats, 1, 20, "games per mode; the median is reported");
    cm.choice("--percepts", m.percepts, {"both", "vision", "oracle"},
              "both (a vision game and an oracle game in turn), vision or oracle");

    BenchPerceptionOptions& p = o.benchPerception;
    Command& cp = leaf(bench, "perception", "the vision's median ms per stage on simulated images", p.common);
    cp.gl();
    seedJsonField(cp);
    cp.text("--lighting", p.lighting, "SPEC", kLightingHelp + ", or sweep (default " + p.lighting + ")");
    cp.count("--frames", p.frames, 1, 10000, "simulated frames");
    cp.count("--repeats", p.repeats, 1, 20, "passes over the frames; the median is reported");
    cp.choice("--camera", p.camera, {"top", "bottom"}, "which camera");

    BenchCalibrationOptions& k = o.benchCalibration;
    Command& ck = leaf(bench, "calibration", "the calibration's parts: sample extraction per camera, each solver", k.common);
    ck.gl();
    seedJsonField(ck);
    k.sim.miscalibration = "random";
    simOptions(ck, k.sim);
    ck.count("--repeats", k.repeats, 1, 20, "rounds of 50 solves per solver");
    ck.number("--time-limit", k.timeLimit, 1, 600, "s", "the calibration phase's time (the rules' 10 min; shorter for a quick look)");
  }
  {
    PerceiveOptions& p = o.perceive;
    Command& c = leaf(root, "perceive", "the vision on one PNG, JPEG or raw YUYV image: JSON and an annotated PNG", p.common);
    c.positionalFile("IMAGE", p.image, "the image (PNG, JPEG, or raw YUYV .yuv/.yuyv/.raw)");
    c.json();
    c.field(kFieldFile);
    c.choice("--camera", p.camera, {"top", "bottom"}, "which camera took the image");
    c.numbers("--head", p.head, headElements(), "head angles for the camera matrix (default 0,0)");
    c.numbers("--torso", p.torso, {{"ROLL", "deg", -30, 30}, {"PITCH", "deg", -30, 30}},
              "the torso's roll and pitch (the IMU's angles) for the camera matrix (default 0,0)");
    c.inputFile("--camera-matrix", p.cameraMatrix,
                "the camera matrix the robot recorded with the image (the JSON of "
                "../shared/data/real-goalbox-images/README.md: position, camera_matrix; crossings are drawn); "
                "replaces --head and --torso");
    c.rule([&p] {
      return !p.cameraMatrix.empty() && (p.common.has("--head") || p.common.has("--torso"))
                 ? "--camera-matrix: gives the whole camera pose; --head and --torso are not used with it"
                 : std::string();
    });
    c.size("--size", p.width, p.height, "size of a raw YUYV file (default: from its length)");
    c.outputFile("--out", p.out, "write the annotated image (PNG)");
    c.count("--scale", p.scale, 1, 8, "scale of the annotated image");
    debugOptions(c, p.debug);
  }
  {
    CLI::App* eval = group("eval", "accuracy against the simulator's truth over many random cases");
    EvalPerceptionOptions& p = o.evalPerception;
    Command& c = leaf(eval, "perception", "the vision against the truth: lines, circle, ball, per lighting", p.common);
    c.gl();
    seedJsonField(c);
    c.count("--trials", p.trials, 1, 10000, "random scenes, each rendered by both cameras");
    c.text("--lighting", p.lighting, "SPEC", "sweep (every preset of the sweep) or " + kLightingHelp + " (default sweep)");
    c.text("--venue", p.venue, "NAME", kVenueLookHelp + "; random: trial t at the look of seed + t (default random)",
           venueProblem);
    c.number("--max-offset", p.maxOffset, 0, 10, "deg", "injected camera offsets, uniform in +-DEG, told to the model");
    c.outputFolder("--images", p.images, "write annotated frames to DIR");
    c.count("--images-every", p.imagesEvery, 1, 10000, "annotate every N-th scene")->needs("--images");
    c.outputFolder("--failures", p.failures, "write frames with a miss or a false detection to DIR");
    c.choice("--percepts", p.percepts, {"vision", "oracle"},
             "vision (render, run the camera pipeline) or oracle (the fast percept mode's error model, "
             "config/parameters/OracleVision.json; no rendering)");
    c.outputFile("--fit-oracle", p.fitOracle,
                 "fit the fast percept mode's error model to the vision's figures and write it (the format of "
                 "config/parameters/OracleVision.json)");
    c.rule([&p] {
      return p.percepts == "oracle" && !p.fitOracle.empty() ? "--fit-oracle: fits the vision, not with --percepts oracle"
                                                            : std::string();
    });
    debugOptions(c, p.debug);

    EvalRealOptions& er = o.evalReal;
    Command& cr = leaf(eval, "real",
                       "the vision and the calibration's sample extraction on real images with line labels and the "
                       "recorded camera matrix (../shared/data/real-goalbox-images/README.md): labelled lines found, "
                       "samples accepted and right",
                       er.common);
    cr.json();
    cr.field(kFieldFile);
    cr.text("--dir", er.dir, "DIR", "the folder of images (NAME.jpg or .png) and their labels (NAME.json)",
            [](const std::string& d) {
              std::error_code ec;
              if (!std::filesystem::exists(d, ec)) return std::string("not found");
              if (!std::filesystem::is_directory(d, ec)) return std::string("not a folder");
              return std::string();
            })
        ->required();
    cr.outputFolder("--failures", er.failures,
                    "write an annotated picture of each image with a labelled line missed or no right sample to DIR");

    EvalCalibrationOptions& k = o.evalCalibration;
    Command& ck = leaf(eval, "calibration", "the robot program calibrates itself (phase 1) with random offsets, lightings and start sides: errors against the injected truth", k.common);
    ck.gl();
    seedJsonField(ck);
    ck.count("--trials", k.trials, 1, 10000, "random cases");
    ck.text("--lighting", k.lighting, "SPEC", "sweep (a random preset of the sweep per case) or " + kLightingHelp + " (default sweep)");
    ck.number("--max-offset", k.maxOffset, 0, 10, "deg", "injected offsets, uniform in +-DEG per parameter");
    ck.choice("--solver", k.solver, {"gauss-newton", "ceres"}, "the solver scored (the other is compared)");
    ck.number("--time-limit", k.timeLimit, 1, 600, "s", "each trial's calibration phase (the rules' 10 min; shorter for a quick look)");
    ck.text("--venue", k.venue, "NAME", kVenueLookHelp + "; random: trial t at the look of seed + t (default random)",
            venueProblem);
    ck.outputFile("--rows", k.rows, "one JSON line per trial, appended as it ends; seeds already in FILE are not run again");
    seedsOption(ck, k.seeds, "--trials");
    ck.outputFolder("--images", k.images,
                    "write each trial's views (annotated and as the robot saw them) and its before/after pictures "
                    "into DIR/seed_S/ (S: the trial's seed)");

    const std::string randomize = "'foreign' robots: link masses +-5%, joint offsets +-1 deg, floor friction 0.6-1.0";
    ck.flag("--randomize", k.randomize, randomize + " (the head's aside)");
    debugOptions(ck, k.debug);

    EvalLocalizationOptions& l = o.evalLocalization;
    Command& cl = leaf(eval, "localization",
                       "the robot program's self-localization and ball model against the truth: scripted walks, "
                       "kidnaps, rolling balls",
                       l.common);
    cl.gl();
    seedJsonField(cl);
    cl.count("--trials", l.trials, 1, 10000, "trials; trial i has seed --seed + i");
    cl.text("--lighting", l.lighting, "SPEC",
            "sweep (trial seed s takes preset s mod 7 of the sweep) or " + kLightingHelp + " (default sweep)");
    cl.flag("--randomize", l.randomize,
            randomize + " (the head's calibrated away), camera offsets +-3 deg the robot was calibrated for "
                        "(residual +-0.15 deg)");
    cl.number("--seconds", l.seconds, 5, 600, "s", "the scripted walk of each trial (a kidnap or a kick follows)");
    cl.count("--kidnap-every", l.kidnapEvery, 0, 1000, "trial seeds s with s mod N = N-1 end with a kidnap (0: none)");
    cl.count("--roll-every", l.rollEvery, 0, 1000, "trial seeds s with s mod N = 1 end with a rolling ball (0: none)");
    cl.choice("--percepts", l.percepts, {"vision", "oracle"}, kPerceptsHelp);
    seedsOption(cl, l.seeds, "--trials");
    cl.outputFile("--rows", l.rows,
                  "one JSON line per trial, appended as it ends; seeds already in FILE are not run again");
    debugOptions(cl, l.debug);
    EvalChallengeOptions& ec = o.evalChallenge;
    Command& cc = leaf(eval, "challenge",
                       "many seeded calibration challenges (both phases): per category median, p95 and worst, "
                       "terminations by reason, the failed trials by seed",
                       ec.common);
    cc.gl();
    seedJsonField(cc);
    cc.count("--trials", ec.trials, 1, 100000, "trials; trial i has seed --seed + i (its offsets, start, balls, robot)");
    cc.text("--lighting", ec.lighting, "SPEC",
            "sweep (trial seed s takes preset s mod 7 of the sweep) or " + kLightingHelp + " (default sweep)");
    cc.flag("--randomize", ec.randomize, randomize + " (the head's aside)");
    cc.flag("--skip-calibration", ec.skipCalibration, "no phase 1: phase 2 with the factory calibration (the baseline)");
    cc.text("--venue", ec.venue, "NAME", kVenueHelp, venueProblem);
    cc.number("--max-offset", ec.maxOffset, 0, 6, "deg", "injected camera offsets uniform in +-this per parameter");
    cc.number("--time-limit", ec.timeLimit, 1, 600, "s", "each phase's time (the rules' 10 min; shorter for a quick look)");
    cc.inputFile("--model", ec.model, "the robot's MJCF (default models/nao_v6.xml)");
    seedsOption(cc, ec.seeds, "--trials");
    cc.outputFile("--rows", ec.rows, "one JSON line per trial, appended as it ends; seeds already in FILE are not run again");
    EvalMatchOptions& em = o.evalMatch;
    Command& cm = leaf(eval, "match",
                       "many seeded 1vs1 games, our robot program at home: wins, draws, losses, points per minute and "
                       "by kind, referee calls by rule, falls and penalties per game",
                       em.common);
    cm.gl();
    seedJsonField(cm);
    cm.text("--lighting", em.lighting, "SPEC",
            "sweep (game seed s takes preset s mod 7 of the sweep) or " + kLightingHelp + " (default sweep)");
    cm.inputFile("--model", em.model, "the robot's MJCF (default models/nao_v6.xml)");
    cm.count("--games", em.games, 1, 100000, "games; game i has seed --seed + i");
    cm.number("--half", em.halfSeconds, 10, 600, "s", "the length of a half (the rules' 5 min)");
    cm.number("--seconds", em.seconds, 1, 7200, "s", "stop each game after this much simulated time (unless given: whole games)");
    cm.flag("--randomize", em.randomize, randomize);
    cm.choice("--opponent", em.opponent, {"self", "baseline"}, kOpponentHelp, "DIR", opponentConfigProblem);
    cm.choice("--percepts", em.percepts, {"vision", "oracle"}, kPerceptsHelp);
    seedsOption(cm, em.seeds, "--games");
    cm.outputFile("--rows", em.rows, "one JSON line per game, appended as it ends; seeds already in FILE are not run again");
    EvalMotionOptions& w = o.evalWalk;
    w.seconds = 60;
    Command& cw = leaf(eval, "walk", "random walk commands every 2-5 s: falls, odometry error", w.common);
    cw.seed();
    cw.json();
    cw.field("a motion test floor without lines");
    cw.count("--trials", w.trials, 1, 1000, "trials");
    cw.number("--seconds", w.seconds, 1, 600, "s", "seconds per trial");
    cw.flag("--randomize", w.randomize, randomize);
    debugOptions(cw, w.debug);

    EvalMotionOptions& t = o.evalWalkTo;
    Command& ct = leaf(eval, "walk-to", "walk to targets 3 m away on odometry alone: final error against the truth", t.common);
    ct.seed();
    ct.json();
    ct.count("--trials", t.trials, 1, 1000, "targets");
    ct.flag("--randomize", t.randomize, randomize);

    EvalMotionOptions& g = o.evalGetUp;
    g.seconds = 15;
    Command& cg = leaf(eval, "getup", "lying on the front and on the back, asked to stand: success within the limit", g.common);
    cg.seed();
    cg.json();
    cg.count("--trials", g.trials, 1, 1000, "trials per side");
    cg.number("--seconds", g.seconds, 1, 120, "s", "the time limit per trial");
    cg.flag("--randomize", g.randomize, randomize);
  }
  {
    WalkOptions& w = o.walk;
    Command& c = leaf(root, "walk", "walk at a speed (or --to a target) in the simulator: speed, falls, odometry error", w.common);
    c.seed();
    c.json();
    c.field("a motion test floor without lines");
    c.flag("--randomize", w.randomize, "a 'foreign' robot: link masses +-5%, joint offsets +-1 deg, floor friction 0.6-1.0");
    auto* vx = c.number("--vx", w.vx, -1000, 1000, "mm/s", "forward speed (the walk clips it to what it can)");
    auto* vy = c.number("--vy", w.vy, -1000, 1000, "mm/s", "sideways speed, left positive");
    auto* vt = c.number("--vtheta", w.vtheta, -1000, 1000, "deg/s", "turn rate, counter-clockwise positive");
    auto* secs = c.number("--seconds", w.seconds, 0.1, 3600, "s", "how long to walk; then the robot stops");
    c.numbers("--to", w.to, {{"X", "m", -10, 10}, {"Y", "m", -10, 10}, {"THETA_DEG", "deg", -180, 180}},
              "instead: walk to this robot-relative target on odometry")
        ->excludes(vx)
        ->excludes(vy)
        ->excludes(vt)
        ->excludes(secs);
    debugOptions(c, w.debug);
  }
  {
    KickOptions& k = o.kick;
    Command& c = leaf(root, "kick", "kicks in the simulator: ball travel, direction error, falls", k.common);
    c.seed();
    c.json();
    c.count("--trials", k.trials, 1, 1000, "kicks");
    c.flag("--randomize", k.randomize, "a 'foreign' robot per trial: masses +-5%, joint offsets +-1 deg, friction 0.6-1");
  }
  {
    CLI::App* train = group("train", "fit a model to the simulator: ball (classifier), friction (ball roll)");
    TrainBallOptions& t = o.trainBall;
    Command& c = leaf(train, "ball", "the ball classifier (HOG + multi-layer perceptron) from simulated images", t.common);
    c.gl();
    seedJsonField(c);
    c.count("--scenes", t.scenes, 5, 100000, "random scenes, each rendered by both cameras (every fifth held out)");
    c.count("--lightings", t.lightings, 1, 5, "random lightings per scene and camera");
    c.count("--hidden", t.hidden, 2, 1000, "neurons in the hidden layer");
    c.count("--iterations", t.iterations, 1, 100000, "training epochs");
    c.text("--samples", t.samples, "FILE",
           "reuse the rendered samples in FILE if it exists, else render them and write them there",
           [](const std::string& s) {
             const std::string in = io::outputFileProblem(s);
             std::error_code ec;
             if (std::filesystem::is_regular_file(s, ec)) return std::string();
             return in.empty() ? in : "'" + s + "': " + in;
           });
    c.outputFile("--out", t.out, "the model to write (default models/vision/ball_classifier.yml in the source tree)");

    TrainFrictionOptions& f = o.trainFriction;
    Command& cf = leaf(train, "friction",
                       "the ball model's rolling deceleration fitted to the simulator's ball: rolls on the empty field, "
                       "stop positions against the model's",
                       f.common);
    seedJsonField(cf);
    cf.count("--rolls", f.rolls, 2, 200, "rolls, speeds evenly spaced from --min-speed to --max-speed");
    cf.number("--min-speed", f.minSpeed, 0.2, 6, "m/s", "the slowest roll's start speed");
    cf.number("--max-speed", f.maxSpeed, 0.2, 6, "m/s", "the fastest roll's start speed");
    cf.rule([&f] {
      return f.minSpeed > f.maxSpeed ? std::string("--min-speed: above --max-speed") : std::string();
    });
  }
  {
    ChallengeCommandOptions& k = o.challenge;
    Command& c = leaf(root, "calibration-challenge", "the whole Autonomous Calibration Challenge, headless: the robot program calibrates itself (phase 1), then reports both balls and walks to three spots (phase 2), scored as the referee scores", k.common);
    c.gl();
    seedJsonField(c);
    simOptions(c, k.sim, true, false);
    c.choice("--start", k.start, {"left", "right", "seed"}, "the side line the robot starts on (seed: drawn from --seed)");
    c.flag("--randomize", k.randomize, "a 'foreign' robot: link masses +-5%, joint offsets +-1 deg (the head's aside), floor friction 0.6-1.0");
    c.number("--time-limit", k.timeLimit, 1, 600, "s", "each phase's time (the rules' 10 min; shorter for a quick look: a phase over it terminates the run)");
    c.flag("--skip-calibration", k.skipCalibration, "no phase 1: phase 2 with the factory calibration (the fast, imprecise baseline)");
    c.text("--venue", k.venue, "NAME", kVenueHelp, venueProblem);
    c.number("--max-offset", k.maxOffset, 0, 6, "deg", "--miscalibration random: offsets uniform in +-this per parameter");
    c.outputFile("--record", k.record, "write phase 1's calibration log (calibrate --from-log solves from it)");
    c.rule([&k] {
      return k.skipCalibration && !k.record.empty() ? std::string("--record: --skip-calibration has no phase 1 to record") : std::string();
    });
    c.outputFolder("--images", k.images, "write the calibration's views, the before/after pictures and a top-down picture of the run");
    debugOptions(c, k.debug);
  }
  {
    MatchOptions& k = o.match;
    Command& c = leaf(root, "match", "a simulated 1vs1 game of the 2021 rules: two robot programs, the GameController's packets, the referee's calls from the simulator's truth", k.common);
    c.gl();
    seedJsonField(c);
    simOptions(c, k.sim, false);
    c.number("--seconds", k.seconds, 1, 7200, "s", "stop after this much simulated time (unless given: the whole game, both halves and any extensions)");
    c.number("--half", k.halfSeconds, 10, 600, "s", "the length of a half (the rules' 5 min)");
    c.flag("--randomize", k.randomize, "'foreign' robots: link masses +-5%, joint offsets +-1 deg, floor friction 0.6-1.0");
    c.choice("--opponent", k.opponent, {"self", "baseline"}, kOpponentHelp, "DIR", opponentConfigProblem);
    c.choice("--percepts", k.percepts, {"vision", "oracle"}, kPerceptsHelp);
    c.inputFile("--situation", k.situation,
                "play a scripted situation instead of a game (JSON: the GameController's state and clock, robots "
                "placed and scripted or running their program, balls placed or kicked; docs/match/README.md)");
    c.outputFile("--replay", k.replay,
                 "write the game's replay: one self-contained HTML page (the field from above, true and believed "
                 "poses, true and modelled balls, the referee's calls on a timeline)");
    c.outputFolder("--images", k.images,
                   "write pictures into DIR: the field from above (true and believed poses and balls) every 10 "
                   "simulated s, at each point and referee call and at the end; with the vision, both robots' "
                   "camera images at those moments");
    debugOptions(c, k.debug);
    c.choice("--gc", k.gc, {"inprocess", "udp"},
             "who runs the game: inprocess (the simulated GameController) or udp (an external GameController on "
             "this machine's network: its packets on --gc-port go to both robots, their return packets to its "
             "--gc-return-port; teams 5 (home) and 6 (away); the simulation keeps real time; the referee's calls "
             "and points are logged for the operator)");
    auto* port = c.count("--gc-port", k.gcPort, 1, 65535, "udp: the GameController's port (default 3838)");
    auto* returnPort = c.count("--gc-return-port", k.gcReturnPort, 1, 65535, "udp: the return packets' port (default 3939)");
    c.rule([&k, port, returnPort] {
      if ((port->count() > 0 || returnPort->count() > 0) && k.gc != "udp") return std::string("--gc-port and --gc-return-port: only with --gc udp");
      if (k.gc == "udp" && !k.situation.empty()) return std::string("--gc udp: runs a game, not a --situation");
      return std::string();
    });
  }
  {
    BatchOptions& b = o.batch;
    Command& c = leaf(root, "batch",
                      "an evaluation (eval challenge|match|localization|calibration and its options) split into chunks of seeds "
                      "on a runner: processes here, GNU parallel (over ssh hosts too) or a Slurm job array; the "
                      "chunks' rows merged into the evaluation's own aggregate",
                      b.common);
    c.json();
    c.choice("--runner", b.runner, {"local", "parallel", "slurm"},
             "local: processes on this machine; parallel: GNU parallel (--sshlogin spreads it over hosts); slurm: "
             "one job array (sbatch; SLURM_CONF chooses the cluster, tools/slurm-local.sh makes one here)");
    c.outputFolder("--dir", b.dir,
                   "the batch's folder: its plan, one rows file and one log per chunk, the merged rows and aggregate "
                   "(default batch-TARGET, e.g. batch-challenge)");
    c.count("--chunk", b.chunk, 0, 100000,
            "seeds per task (0: the evaluation's own, about a minute of work or more: 1 challenge, game or calibration, 4 "
            "localization trials)");
    c.count("--jobs", b.jobs, 0, 4096, "tasks at once for local and parallel (0: one per core)");
    auto* ssh = c.text("--sshlogin", b.sshlogin, "HOSTS",
                       "parallel: GNU parallel's --sshlogin (hosts with this program at the same path, the batch "
                       "folder on a shared file system)",
                       [](const std::string& s) { return s.empty() ? std::string("an empty host list") : std::string(); });
    c.flag("--resume", b.resume, "continue the batch in --dir: only the seeds without a row run");
    c.app()->allow_extras();
    c.rule([&b, ssh] {
      if (ssh->count() > 0 && b.runner != "parallel") return std::string("--sshlogin: only for --runner parallel");
      return std::string();
    });
    c.rule([&b, app = c.app()] {
      b.evalArgs = app->remaining();
      checkBatchEval(b.evalArgs);
      return std::string();
    });
  }
  {
    ModulesOptions& m = o.modules;
    Command& c = leaf(root, "modules", "every module of the robot program: cadence, requires, provides (or a Graphviz graph)", m.common);
    c.json();
    c.flag("--dot", m.dot, "print the module graph as Graphviz (providers as config/modules.json chooses them)");
    c.rule([&m] {
      return m.dot && m.common.json == "-" ? std::string("--dot: the graph takes stdout; give --json a file") : std::string();
    });
  }
  {
    CalibrateOptions& k = o.calibrate;
    Command& c = leaf(root, "calibrate", "the robot program calibrates its six camera offsets from the goal box, from the challenge's start (sim): true against estimated", k.common);
    c.gl();
    seedJsonField(c);
    simOptions(c, k.sim);
    c.choice("--solver", k.solver, {"gauss-newton", "ceres"}, "least-squares solver (default: the robot program's, config/parameters/Calibrator.json)");
    c.flag("--compare", k.compare, "also solve the same samples with the other solver");
    c.choice("--lines", k.lines, {"lsd", "vision", "lsd+vision"},
             "image line segments from OpenCV's LSD, the vision pipeline, or LSD then the vision (default: the robot program's, config/parameters/Calibrator.json)");
    c.choice("--start", k.start, {"left", "right"}, "the side line the robot starts on");
    c.number("--time-limit", k.timeLimit, 1, 600, "s", "the calibration phase's time (the rules' 10 min; shorter for a quick look)");
    c.outputFolder("--images", k.images, "write every view annotated and the before/after pictures (paper Fig. 2)");
    c.outputFile("--record", k.record, "write the calibration log: every image the robot's Calibrator judged, with its joints and IMU angle");
    auto* fromLog = c.inputFile("--from-log", k.fromLog,
                                "no simulator: the robot program's Calibrator solves from a recorded calibration log (--record; run --backend nao --record)");
    c.text("--head-id", k.headId, "ID", "--from-log: the robot being calibrated; a log another head recorded is refused")->needs(fromLog);
    c.rule([&k] {
      if (k.fromLog.empty()) return std::string();
      for (const char* flag : {"--lighting", "--miscalibration", "--model", "--start", "--images", "--record", "--seed", "--time-limit"})
        if (k.common.has(flag)) return std::string("--from-log: ") + flag + " is for the simulator, which a log replaces";
      return std::string();
    });
    debugOptions(c, k.debug);
    auto* save = c.flag("--save", k.save, "store an accepted result for this robot's head id (refused above the residual threshold)");
    c.outputFolder("--store", k.store, "calibration folder for --save (default config/calibration)")->needs(save);
    c.rule([&k] {
      if (!k.save || !k.store.empty()) return std::string();
      const std::string store = dataPath("config/calibration");
      const std::string problem = io::outputDirectoryProblem(store);
      return problem.empty() ? problem : "--save: the default store " + store + ": " + problem;
    });
  }
}

}  // namespace nao::cli
