// The match replay (scenarios/MatchReplay.h) in a real headless browser (Debian's
// chromium-headless-shell, installed by .ci/install-deps.sh): the page loads without script
// errors, holds every frame and event, opened at #t=T it shows the moment T: a screenshot has the
// ball where the frames put it and not where it lay before. Then a real game's replay from
// `match --replay`: its frames and events are those of the game's JSON.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "scenarios/MatchReplay.h"
#include "support/RunCommand.h"

namespace {

namespace fs = std::filesystem;
const char* kBrowser = "/usr/bin/chromium-headless-shell";
const std::string kWindow = "--window-size=1200,1300 --force-device-scale-factor=1";

bool browserMissing() {
  if (fs::exists(kBrowser)) return false;
  // CI installs it (.ci/install-deps.sh): there its absence is a failure, not a skip.
  if (std::getenv("CI")) ADD_FAILURE() << kBrowser << " is missing: .ci/install-deps.sh installs chromium-headless-shell";
  return true;
}

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  pclose(p);
  return out;
}

std::string browser(const std::string& args, const fs::path& page, const std::string& fragment) {
  return std::string("timeout -s KILL 60 ") + kBrowser + " --no-sandbox --disable-gpu " + kWindow + " " + args + " 'file://" +
         page.string() + fragment + "' 2>/dev/null";
}

// The body's data-NAME attribute in the DOM the browser dumped after running the page.
std::string attribute(const std::string& dom, const std::string& name) {
  const auto body = dom.find("<body");
  if (body == std::string::npos) return "";
  const std::string tag = dom.substr(body, dom.find('>', body) - body);
  const std::string key = " data-" + name + "=\"";
  const auto at = tag.find(key);
  if (at == std::string::npos) return "";
  const auto start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

struct Page {
  std::string dom;
  cv::Mat shot;
  cv::Point canvas;
};

Page open(const fs::path& page, double t) {
  Page p;
  const std::string fragment = "#t=" + std::to_string(t);
  p.dom = run(browser("--dump-dom", page, fragment));
  const fs::path png = page.parent_path() / "shot.png";
  fs::remove(png);
  run(browser("--screenshot=" + png.string(), page, fragment));
  p.shot = cv::imread(png.string());
  const std::string at = attribute(p.dom, "canvas");
  const auto comma = at.find(',');
  if (comma != std::string::npos) p.canvas = {std::stoi(at.substr(0, comma)), std::stoi(at.substr(comma + 1))};
  return p;
}

bool orangeAt(const Page& p, const nao::FieldDimensions& f, const Eigen::Vector2d& field) {
  const Eigen::Vector2d px = nao::sim::replayPixel(f, field);
  const cv::Point at(p.canvas.x + static_cast<int>(std::lround(px.x())), p.canvas.y + static_cast<int>(std::lround(px.y())));
  if (at.x < 0 || at.y < 0 || at.x >= p.shot.cols || at.y >= p.shot.rows) return false;
  const cv::Vec3b c = p.shot.at<cv::Vec3b>(at);  // BGR
  return c[2] > 230 && c[1] > 100 && c[1] < 160 && c[0] < 40;
}

TEST(MatchReplay, TheBrowserShowsTheBallWhereTheFramesPutIt) {
  if (browserMissing()) GTEST_SKIP() << "no " << kBrowser;
  const nao::FieldDimensions f;
  std::vector<nao::sim::ReplayFrame> frames;
  auto ballAt = [](double t) { return Eigen::Vector2d(-3 + 1.2 * t, 1.5 - 0.5 * t); };  // a ball crossing the field
  for (int i = 0; i < 50; ++i) {
    nao::sim::ReplayFrame fr;
    fr.t = 0.1 * i;
    fr.state = "PLAYING";
    fr.robots[0].pose = {-1, -1, 0.3};
    fr.robots[1].pose = {1.5, 1, 3.0};
    fr.robots[1].beliefValid = true;
    fr.robots[1].belief = {1.6, 0.9, 3.0};
    fr.balls = {ballAt(fr.t), Eigen::Vector2d(0, -2.5)};
    frames.push_back(fr);
  }
  const nlohmann::json events = {{{"t", 0.5}, {"kind", "gc_state"}, {"text", "PLAYING </script> <b>"}},
                                 {{"t", 2.0}, {"kind", "call"}, {"rule", "halfway_line"}, {"team", "home"}},
                                 {{"t", 4.2}, {"kind", "point"}, {"team", "away"}, {"how", "goal"}}};
  const fs::path dir = fs::path(::testing::TempDir()) / "match_replay_synthetic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path page = dir / "replay.html";
  std::ofstream(page) << nao::sim::replayHtml(nao::sim::replayData(f, frames, events));

  const Page p = open(page, 3.0);
  ASSERT_EQ(attribute(p.dom, "ready"), "1") << p.dom.substr(0, 2000);
  EXPECT_EQ(attribute(p.dom, "errors"), "0");
  EXPECT_EQ(attribute(p.dom, "frames"), "50");
  EXPECT_EQ(attribute(p.dom, "events"), "3");
  EXPECT_EQ(attribute(p.dom, "time"), "3");
  ASSERT_FALSE(p.shot.empty());
  EXPECT_TRUE(orangeAt(p, f, ballAt(3.0))) << "the ball at 3 s";
  EXPECT_TRUE(orangeAt(p, f, Eigen::Vector2d(0, -2.5))) << "the ball lying still";
  EXPECT_FALSE(orangeAt(p, f, ballAt(0.5))) << "the ball is no longer where it was at 0.5 s";
  const Page early = open(page, 0.5);
  EXPECT_TRUE(orangeAt(early, f, ballAt(0.5)));
  EXPECT_FALSE(orangeAt(early, f, ballAt(3.0)));
  fs::remove_all(dir);
}

TEST(MatchReplay, AGamesReplayHoldsItsFramesAndEvents) {
  if (browserMissing()) GTEST_SKIP() << "no " << kBrowser;
  const fs::path dir = fs::path(::testing::TempDir()) / "match_replay_game";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = nao::test::runCommand("match --seconds 6 --opponent baseline --replay " + (dir / "game.html").string() +
                                       " --json " + (dir / "game.json").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(dir / "game.json");
  const nlohmann::json game = nlohmann::json::parse(in);
  const Page p = open(dir / "game.html", 4.0);
  ASSERT_EQ(attribute(p.dom, "ready"), "1");
  EXPECT_EQ(attribute(p.dom, "errors"), "0");
  EXPECT_EQ(attribute(p.dom, "events"), std::to_string(game["events"].size()));
  const int frames = std::stoi(attribute(p.dom, "frames"));
  EXPECT_NEAR(frames, 60, 1) << "ten frames a simulated second";
  // The page shows the last frame not after 4 s: at most a frame's 0.1 s and a cycle earlier.
  const double shown = std::stod(attribute(p.dom, "time"));
  EXPECT_LE(shown, 4.0);
  EXPECT_GE(shown, 4.0 - 0.1 - 0.013);
  fs::remove_all(dir);
}

}  // namespace
