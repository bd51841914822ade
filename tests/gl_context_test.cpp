// The cameras' OpenGL chosen at run time (--gl): EGL on Mesa's software device renders what
// OSMesa renders, bench names the renderer, a process keeps to one API, and a bad choice is a
// one-line error. EGL runs in child processes (nao-soccer): MuJoCo's GL loader would take EGL's
// functions for any later OSMesa context of the same process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "sim/GlContext.h"
#include "tests/support/RunCommand.h"

namespace {

namespace fs = std::filesystem;

using Output = nao::test::SplitResult;

Output run(const std::string& args, const std::string& env = "") { return nao::test::runCommandSplit(args, 300, env); }

std::string bytes(const fs::path& file) {
  std::ifstream f(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

TEST(GlContext, BenchSimRendersThroughEglAndNamesItsRenderer) {
  const Output o = run("bench sim --gl egl --seconds 1 --repeats 1 --json -");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["gl_platform"].get<std::string>().rfind("egl", 0), 0u) << o.out;
  EXPECT_FALSE(j["gl_vendor"].get<std::string>().empty());
  EXPECT_FALSE(j["gl_renderer"].get<std::string>().empty());
  EXPECT_GT(j["render_ms_top"].get<double>(), 0);
  const Output m = run("bench sim --gl osmesa --seconds 1 --repeats 1 --json -");
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(nlohmann::json::parse(m.out)["gl_platform"], "osmesa");
}

// On a CPU both are Mesa's llvmpipe: the same camera image, byte for byte (with a GPU, EGL's
// image is its own and only has to exist).
TEST(GlContext, EglOnMesasSoftwareDeviceRendersWhatOsMesaRenders) {
  const fs::path dir = fs::path(::testing::TempDir()) / "gl_context";
  fs::create_directories(dir);
  const std::string view = " render --camera top --pose -1,0.5,20 --head 10,20 --lighting shadows";
  const Output e = run(view + " --gl egl --out " + (dir / "egl.png").string());
  const Output o = run(view + " --gl osmesa --out " + (dir / "osmesa.png").string());
  ASSERT_EQ(e.code, 0) << e.err;
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(run("bench sim --gl egl --seconds 1 --repeats 1 --json -").out, nullptr, false);
  ASSERT_TRUE(j.is_object());
  EXPECT_GT(bytes(dir / "egl.png").size(), 10000u);
  if (j["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(bytes(dir / "egl.png") == bytes(dir / "osmesa.png")) << "EGL's and OSMesa's images differ";
  }
}

TEST(GlContext, BadChoicesAreOneLineErrors) {
  const std::string out = (fs::path(::testing::TempDir()) / "gl_context_bad.png").string();
  const Output unknown = run("render --camera top --gl vulkan --out " + out);
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("--gl"), std::string::npos) << unknown.err;
  const Output device = run("render --camera top --gl egl --out " + out, "MUJOCO_EGL_DEVICE_ID=99");
  EXPECT_EQ(device.code, 2);
  EXPECT_NE(device.err.find("MUJOCO_EGL_DEVICE_ID"), std::string::npos) << device.err;
  for (const Output& o : {unknown, device})
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
}

// In this process: OSMesa only (see the top).
TEST(GlContext, AProcessKeepsToTheApiOfItsFirstContext) {
  using namespace nao::sim;
  EXPECT_EQ(parseGlApi("osmesa"), GlApi::OsMesa);
  EXPECT_EQ(parseGlApi("egl"), GlApi::Egl);
  EXPECT_EQ(parseGlApi("auto"), GlApi::Auto);
  EXPECT_FALSE(parseGlApi("gl"));
  setGlApi(GlApi::OsMesa);
  GlContext first;
  first.makeCurrent(64, 48);
  EXPECT_EQ(first.platform(), "osmesa");
  EXPECT_FALSE(first.renderer().empty());
  EXPECT_THROW(setGlApi(GlApi::Egl), nao::Error);
  setGlApi(GlApi::Auto);  // auto keeps to what this process already renders through
  GlContext second;
  EXPECT_EQ(second.platform(), "osmesa");
}

}  // namespace
