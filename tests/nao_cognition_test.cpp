// `run --backend nao` with the full cognition, end to end. First the project's LoLA peer
// (tests/lola_peer.cpp, a separate process judging every answer against the 12 ms cycle) runs
// the real nao-soccer with --cameras files:DIR, where DIR holds frames the simulator rendered
// here (`nao-soccer render`), fed through the NAO backend's camera hand-off at 30 Hz each.
// Motion answers every LoLA packet in time while cognition runs on both cameras in its own
// thread; an image cognition had no time for is dropped and counted. Then the simulator as a
// whole NAO (tests/sim_lola_peer.cpp). And the program is built for the head LoLA names (its
// parameter overlay).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "perception/calibration/CalibrationLog.h"
#include "tests/support/RunCommand.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

bool quick() { return std::getenv("NAO_TEST_QUICK") != nullptr; }  // the sanitizer run

// Runs a shell command line: its wait status and what it wrote (stdout and stderr).
std::pair<int, std::string> shell(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, "popen failed: " + cmd};
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, p)) out += buffer;
  return {pclose(p), out};
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream f(path);
  EXPECT_TRUE(f.good()) << path;
  return f ? nlohmann::json::parse(f) : nlohmann::json::object();
}

TEST(NaoCognition, FileCamerasThroughTheLolaPeerWithoutALateAnswer) {
  // Real time is the Release stage's to judge: under the sanitizers the program runs at several
  // times its cost and answers late (measured: a dozen answers 12-18 ms late in 10 s).
  if (quick()) GTEST_SKIP() << "real-time answers: the Release stage runs it";
  const fs::path dir = fs::path(::testing::TempDir()) / "nao_cognition_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "frames" / "top");
  fs::create_directories(dir / "frames" / "bottom");
  // Three views near the own penalty area: lines, the penalty mark and a ball in front.
  const char* poses[] = {"-3.2,-0.5,0", "-3.0,0.8,-20", "-2.6,-1.2,25"};
  for (int i = 0; i < 3; ++i)
    for (const char* camera : {"top", "bottom"}) {
      const std::string out = (dir / "frames" / camera / ("frame" + std::to_string(i) + ".png")).string();
      const auto r = test::runCommand(std::string("render --camera ") + camera + " --pose " + poses[i] +
                                          " --head 0,10 --ball -2.2,-0.2 --out " + out,
                                      120);
      ASSERT_EQ(r.code, 0) << r.out;
    }

  // LoLA time: 30 s (10 s in the sanitizer run); then SIGTERM, and the program writes its JSON.
  const int seconds = quick() ? 10 : 30;
  const fs::path runJson = dir / "run.json", peerJson = dir / "peer.json", log = dir / "views.calog";
  const std::string cmd = std::string(LOLA_PEER) + " --nao-soccer " + NAO_BINARY + " --soak " + std::to_string(seconds) +
                          " --cameras files:" + (dir / "frames").string() + " --arg --json --arg " + runJson.string() +
                          " --arg --record --arg " + log.string() + " --json " + peerJson.string() + " 2>&1";
  const auto [status, out] = shell(cmd);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;

  // The peer's own measurement: every answer within the cycle but while the machine itself
  // stalled (its probe thread held up as long: tests/support/StallProbe.h), every check passed.
  const nlohmann::json peer = readJson(peerJson);
  EXPECT_EQ(peer.value("late_answers", -1) - peer.value("late_in_machine_stalls", 0), 0) << out;
  EXPECT_EQ(peer.value("checks_failed", -1), 0) << out;
  EXPECT_GE(peer.value("normal_cycles", 0), seconds * 80);

  // The program's: the same, from its side, and cognition on both cameras.
  const nlohmann::json run = readJson(runJson);
  ASSERT_TRUE(run.contains("lola")) << run.dump();
  const nlohmann::json& lola = run["lola"];
  // Its late answers (packet arrival to answer, the same monotonic clock) only while the machine
  // itself stalled: a stall of the program's CPU is the host's, not the program's.
  int lateOutsideStalls = 0;
  for (const auto& t : lola.value("late_answer_times", nlohmann::json::array())) {
    bool stalled = false;
    for (const auto& s : peer["machine_stalls"].value("intervals", nlohmann::json::array()))
      stalled = stalled || (s[0].get<double>() < t[1].get<double>() && s[1].get<double>() > t[0].get<double>());
    lateOutsideStalls += !stalled;
  }
  EXPECT_EQ(lateOutsideStalls, 0) << lola.dump() << "\n" << peer["machine_stalls"].dump();
  EXPECT_EQ(lola["answered"], lola["cycles"]);
  EXPECT_LT(lola["cycle_ms_p99"].get<double>(), 12.0);
  EXPECT_TRUE(run["clean_stop"].get<bool>());
  // The frames come at 30 Hz per camera for as long as LoLA ran: each was processed, or dropped
  // because a newer one of its camera was waiting.
  const double expected = lola["cycles"].get<double>() * 0.012 * 30;
  for (const char* camera : {"top", "bottom"}) {
    const long processed = run["images_processed"][camera].get<long>();
    const long dropped = run["images_dropped"][camera].get<long>();
    EXPECT_GT(processed, expected / 2) << camera << ": cognition kept up with less than half of the frames";
    EXPECT_GE(processed + dropped, 0.85 * expected) << camera;
    EXPECT_LE(processed + dropped, 1.05 * expected + 2) << camera;
    std::printf("nao cognition: %s %ld processed, %ld dropped of %.0f frames\n", camera, processed, dropped, expected);
  }
  EXPECT_EQ(run["images_skipped"], 0);
  EXPECT_GT(run["cognition"]["ms_per_image"]["mean"].get<double>(), 0);
  std::printf("nao cognition: lola %s, cognition %s, motion CPU %s\n", lola.dump().c_str(), run["cognition"].dump().c_str(),
              run["cpu_ms_per_cycle"].dump().c_str());
  // The program was built for the head LoLA named (its per-robot parameters and calibration).
  EXPECT_EQ(run["robot"]["head_id"], "P0000073A07S8AF00027");
  // --record: the calibration log, under that head, written when the run ended; no calibration
  // ran, so it holds no view, and calibrate --from-log says so.
  const calibration::CalibrationLog calibrationLog = calibration::readCalibrationLog(log.string());
  EXPECT_EQ(calibrationLog.headId, "P0000073A07S8AF00027");
  EXPECT_EQ(calibrationLog.backend, "nao");
  EXPECT_TRUE(calibrationLog.records.empty());
  const auto fromLog = test::runCommand("calibrate --from-log " + log.string());
  EXPECT_EQ(fromLog.code, 2) << fromLog.out;
  EXPECT_NE(fromLog.out.find("holds no views"), std::string::npos) << fromLog.out;
  if (!HasFailure()) fs::remove_all(dir);
}

// The simulator as the whole NAO (tests/sim_lola_peer.cpp): LoLA packets from the simulated
// robot's sensors over the socket, its joints driven by the answers, both cameras rendered from
// the same state and sent to --cameras socket:PATH. The program walks to a pose by its own
// localization; the peer scores its belief against the truth, and the figures agree with
// `run --backend sim` of the same scene.
TEST(NaoCognition, TheSimulatedNaoThroughLolaAndTheCameraSocketLocalizesAndArrives) {
  // As above: under the sanitizers the renders and the program miss the real-time pace.
  if (quick()) GTEST_SKIP() << "real-time answers and frame rates: the Release stage runs it";
  const fs::path dir = fs::path(::testing::TempDir()) / "nao_sim_peer_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int seconds = quick() ? 12 : 20;
  const fs::path peerJson = dir / "peer.json", simJson = dir / "sim.json";
  const std::string scene = " --goto -2,-1.5,0 --ball -1,-1";
  const std::string cmd = std::string(SIM_LOLA_PEER) + " --nao-soccer " + NAO_BINARY + " --seconds " +
                          std::to_string(seconds) + scene + (quick() ? " --sanitized" : "") + " --json " +
                          peerJson.string() + " 2>&1";
  const auto [status, out] = shell(cmd);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  const nlohmann::json peer = readJson(peerJson);
  ASSERT_TRUE(peer.contains("localization_error_m")) << out;
  // Every answer within the cycle, on both sides, but while the machine itself stalled (the
  // peer's probe thread held up as long: tests/support/StallProbe.h; a 2-core CI machine does
  // that now and then). Under the sanitizers, whose peer and program share two cores at
  // several times the cost, at most 1 % over it from the peer's view.
  if (quick()) EXPECT_LE(peer["late_answers"].get<double>(), 0.01 * seconds / 0.012) << out;
  else EXPECT_EQ(peer["late_answers"].get<double>() - peer["late_answers_in_machine_stalls"].get<double>(), 0) << out;
  EXPECT_EQ(peer["missing_answers"], 0) << out;
  EXPECT_GE(peer["cycles_judged"].get<double>(), seconds / 0.012 - 2);
  EXPECT_EQ(peer["program"]["lola"]["late"].get<double>() - peer.value("program_late_in_machine_stalls", 0.0), 0);
  EXPECT_TRUE(peer["program"]["clean_stop"].get<bool>());
  // The frames went through the hand-off: 30 Hz per camera of simulated time, less the few a
  // busy machine made the peer drop (many under the sanitizers, whose renders take longer than
  // a frame); cognition ran on each camera's frames.
  for (const char* camera : {"top", "bottom"}) {
    const double sent = peer["frames_sent"][camera].get<double>();
    EXPECT_GE(sent, (quick() ? 0.3 : 0.8) * 30 * seconds) << camera;
    EXPECT_GE(peer["program"]["images_processed"][camera].get<double>(), 0.9 * sent) << camera;
  }
  // The program chose where each camera meters (AutoExposureWeighting) and the NAO backend sent
  // it over the camera sockets, which the peer renders with, as the sim backend does: the head
  // scans, so the weights change again and again, most of the time uneven (the hall beyond the
  // near field in view), all equal while it looks down at the near field only.
  const nlohmann::json& top = peer["exposure_weights"]["top"];
  EXPECT_GE(top["messages"].get<int>(), 10) << top.dump();
  EXPECT_GE(top["uneven"].get<int>(), top["messages"].get<int>() / 2) << top.dump();
  EXPECT_EQ(top["last"].size(), 16u) << top.dump();
  // The belief against the truth the program never saw.
  EXPECT_EQ(peer["localization_valid_fraction"], 1.0);
  EXPECT_LT(peer["localization_error_m"]["median"].get<double>(), 0.05) << peer.dump();
  EXPECT_LT(peer["heading_error_deg"]["median"].get<double>(), 1.5) << peer.dump();
  EXPECT_GE(peer["ball_error_m"]["samples"].get<int>(), seconds - 4);
  EXPECT_LT(peer["ball_error_m"]["median"].get<double>(), 0.05) << peer.dump();
  if (!quick()) {
    EXPECT_LT(peer["goto"]["position_error_m"].get<double>(), 0.10) << peer.dump();
    EXPECT_LT(peer["goto"]["heading_error_deg"].get<double>(), 5.0) << peer.dump();
  }

  // The same scene on the sim backend: the two beliefs are equally good, within noise.
  const auto r = test::runCommand("run --backend sim --seconds " + std::to_string(seconds) + scene + " --json " +
                                      simJson.string(),
                                  300);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json sim = readJson(simJson);
  const double simError = sim["localization_error_m"]["median"].get<double>();
  const double naoError = peer["localization_error_m"]["median"].get<double>();
  EXPECT_LT(naoError, simError + 0.03) << "nao " << naoError << " m, sim " << simError << " m";
  const double simBall = sim["ball_error_m"]["median"].get<double>();
  const double naoBall = peer["ball_error_m"]["median"].get<double>();
  EXPECT_LT(naoBall, simBall + 0.03) << "nao " << naoBall << " m, sim " << simBall << " m";
  std::printf("nao via sim_lola_peer: localization median %.4f m (sim %.4f m), ball %.4f m (sim %.4f m), %s\n", naoError,
              simError, naoBall, simBall, peer["answer_ms"].dump().c_str());
  if (!HasFailure()) fs::remove_all(dir);
}

// The program is built for the head LoLA's first packet names: that head's parameter overlay
// (config/robots/<head id>/) is read. Proof: a data root whose overlay for the peer's head holds
// an unknown key stops the start with one line naming that file.
TEST(NaoCognition, TheProgramIsBuiltWithTheOverlayOfTheHeadLolaNames) {
  const fs::path home = fs::path(::testing::TempDir()) / "nao_cognition_overlay";
  fs::remove_all(home);
  fs::create_directories(home / "models" / "vision");
  fs::copy(fs::path(NAO_SOURCE_DIR) / "config", home / "config", fs::copy_options::recursive);
  fs::copy_file(fs::path(NAO_SOURCE_DIR) / "models/vision/ball_classifier.yml",
                home / "models/vision/ball_classifier.yml");
  const fs::path overlay = home / "config/robots/P0000073A07S8AF00027/HeadControl.json";  // lola_peer's head
  fs::create_directories(overlay.parent_path());
  std::ofstream(overlay) << "{\"bogus\": 1}\n";
  const fs::path peerJson = home / "peer.json";
  const std::string cmd = "NAO_SOCCER_HOME=" + home.string() + " " + LOLA_PEER + " --nao-soccer " + NAO_BINARY +
                          " --soak 2 --json " + peerJson.string() + " 2>&1";
  const std::string out = shell(cmd).second;  // the peer fails: the program ended at the start
  EXPECT_NE(out.find("run: parameters with this head's " + overlay.parent_path().string() + "/"), std::string::npos)
      << out;
  EXPECT_NE(out.find("nao-soccer run: " + overlay.string() + ": bogus: unknown parameter"), std::string::npos) << out;
  const nlohmann::json peer = readJson(peerJson);
  if (peer.contains("work_dir")) fs::remove_all(peer["work_dir"].get<std::string>());
  if (!HasFailure()) fs::remove_all(home);
}

}  // namespace
}  // namespace nao
