// Debug channels (robot/Debug.h): an unsubscribed channel writes nothing and never builds its
// payload; a subscribed one writes one JSON line per message with its name and the time; an
// unknown name is refused naming the known ones. Through a pipeline: a module's own channel,
// and `timing` naming every module in order.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "robot/Debug.h"
#include "robot/Error.h"
#include "robot/Module.h"

namespace nao {
namespace {

NAO_DEBUG_CHANNEL(kAlpha, "test_alpha", "a test channel");
NAO_DEBUG_CHANNEL(kBeta, "test_beta", "another test channel");

std::vector<nlohmann::json> lines(const std::string& text) {
  std::vector<nlohmann::json> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << "not JSON: " << line;
    out.push_back(j);
  }
  EXPECT_TRUE(text.empty() || text.back() == '\n');
  return out;
}

TEST(Debug, UnsubscribedWritesNothingAndBuildsNoPayload) {
  std::ostringstream sink;
  DebugChannels debug(sink);
  debug.subscribe("test_beta");
  int built = 0;
  debug.emit(kAlpha, [&] {
    ++built;
    return nlohmann::json{{"x", 1}};
  });
  EXPECT_EQ(built, 0);
  EXPECT_FALSE(debug.on(kAlpha));
  EXPECT_EQ(sink.str(), "");
  EXPECT_EQ(debug.linesWritten(), 0);
  // The shared default instance is never subscribed.
  EXPECT_FALSE(DebugChannels::none().any());
}

TEST(Debug, SubscribedWritesOneJsonLinePerMessage) {
  std::ostringstream sink;
  DebugChannels debug(sink);
  debug.subscribe("test_alpha,test_beta");
  debug.setTime(12.5);
  debug.emit(kAlpha, [] { return nlohmann::json{{"x", 1.25}, {"name", "a\"b\n"}}; });
  debug.setTime(12.512);
  debug.write(kBeta, 7);  // not an object: under "value"
  const auto j = lines(sink.str());
  ASSERT_EQ(j.size(), 2u) << sink.str();
  EXPECT_EQ(j[0].at("channel"), "test_alpha");
  EXPECT_DOUBLE_EQ(j[0].at("t").get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j[0].at("x").get<double>(), 1.25);
  EXPECT_EQ(j[0].at("name"), "a\"b\n");
  EXPECT_EQ(j[1].at("channel"), "test_beta");
  EXPECT_DOUBLE_EQ(j[1].at("t").get<double>(), 12.512);
  EXPECT_EQ(j[1].at("value"), 7);
  EXPECT_EQ(sink.str().rfind("{\"channel\":\"test_alpha\",\"t\":12.5,", 0), 0u) << "channel and t lead";
}

// Motion and cognition write from threads of their own on a NAO: each line carries the time of
// the cycle or image its own thread is processing, never the other cadence's.
TEST(Debug, EachThreadsLinesCarryItsOwnTime) {
  std::ostringstream sink;
  DebugChannels debug(sink);
  debug.subscribe("test_alpha,test_beta");
  auto writer = [&debug](const DebugChannel& channel, double base) {
    for (int i = 0; i < 2000; ++i) {
      debug.setTime(base + i);
      std::this_thread::yield();
      debug.write(channel, nlohmann::json{{"i", i}});
    }
  };
  std::thread motion(writer, std::cref(kAlpha), 0.0), cognition(writer, std::cref(kBeta), 1e6);
  motion.join();
  cognition.join();
  const auto j = lines(sink.str());
  ASSERT_EQ(j.size(), 4000u);
  for (const auto& line : j) {
    const double base = line.at("channel") == "test_alpha" ? 0.0 : 1e6;
    EXPECT_DOUBLE_EQ(line.at("t").get<double>(), base + line.at("i").get<double>()) << line.dump();
  }
}

TEST(Debug, UnknownChannelIsRefusedNamingTheKnownOnes) {
  DebugChannels debug;
  try {
    debug.subscribe("test_alpha,nosuch", "--debug");
    FAIL() << "nosuch accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "--debug");
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown channel 'nosuch'"), std::string::npos) << what;
    EXPECT_NE(what.find("test_alpha"), std::string::npos) << what;
    EXPECT_NE(what.find("timing"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  EXPECT_FALSE(debug.on(kAlpha)) << "a refused list subscribes nothing";
  EXPECT_NE(debugChannelsProblem(""), "");
  EXPECT_NE(debugChannelsProblem("test_alpha,"), "");
  EXPECT_EQ(debugChannelsProblem("test_alpha,timing"), "");
  bool listed = false;
  for (const auto& c : debugChannelList()) listed = listed || (c.name == "test_beta" && c.description == "another test channel");
  EXPECT_TRUE(listed);
}

struct Count {
  int value = 0;
};
struct Doubled {
  int value = 0;
};
struct Tripled {
  int value = 0;
};

class Doubler : public Module<Doubler, Requires<Count>, Provides<Doubled>> {
 public:
  int payloads = 0;

 private:
  void update() override {
    out<Doubled>().value = 2 * in<Count>().value;
    debug(kAlpha, [&] {
      ++payloads;
      return nlohmann::json{{"doubled", out<Doubled>().value}, {"debugging", debugging(kAlpha)}};
    });
  }
};
class Tripler : public Module<Tripler, Requires<Count, Doubled>, Provides<Tripled>> {
  void update() override { out<Tripled>().value = in<Doubled>().value + in<Count>().value; }
};

TEST(Debug, PipelineHandsTheChannelsToModulesAndTimesThem) {
  std::ostringstream sink;
  DebugChannels debug(sink);
  Pipeline p;
  auto tripler = std::make_unique<Tripler>();
  auto doubler = std::make_unique<Doubler>();
  Doubler* d = doubler.get();
  p.add(std::move(tripler));
  p.setDebug(&debug, "motion");
  p.add(std::move(doubler));  // added after setDebug: gets the channels too
  p.inputs<Count>();
  Blackboard board;
  board.write<Count>().value = 3;

  p.update(board);  // nothing subscribed
  EXPECT_EQ(d->payloads, 0);
  EXPECT_EQ(sink.str(), "");

  debug.subscribe("test_alpha,timing");
  debug.setTime(0.024);
  p.update(board);
  EXPECT_EQ(d->payloads, 1);
  const auto j = lines(sink.str());
  ASSERT_EQ(j.size(), 2u) << sink.str();
  EXPECT_EQ(j[0].at("channel"), "test_alpha");
  EXPECT_EQ(j[0].at("doubled"), 6);
  EXPECT_EQ(j[0].at("debugging"), true);
  EXPECT_EQ(j[1].at("channel"), "timing");
  EXPECT_DOUBLE_EQ(j[1].at("t").get<double>(), 0.024);
  EXPECT_EQ(j[1].at("pipeline"), "motion");
  const auto& modules = j[1].at("modules");
  ASSERT_EQ(modules.size(), 2u);
  EXPECT_EQ(modules[0].at("module"), "Doubler");  // in pipeline order
  EXPECT_EQ(modules[1].at("module"), "Tripler");
  double sum = 0;
  for (const auto& m : modules) {
    EXPECT_EQ(m.at("cadence"), "motion");
    EXPECT_GE(m.at("ms").get<double>(), 0);
    sum += m.at("ms").get<double>();
  }
  EXPECT_NEAR(j[1].at("total_ms").get<double>(), sum, 1e-9);
  EXPECT_EQ(board.read<Tripled>().value, 9);

  sink.str("");
  p.update(board);
  p.writeTimingSummary();
  const auto s = lines(sink.str());
  ASSERT_EQ(s.size(), 3u) << sink.str();  // alpha, timing, summary
  EXPECT_EQ(s[2].at("summary"), true);
  EXPECT_EQ(s[2].at("runs"), 2);  // the timed runs: the first ran before `timing` was subscribed
  ASSERT_EQ(s[2].at("modules").size(), 2u);
  EXPECT_EQ(s[2].at("modules")[0].at("runs"), 2);
  EXPECT_GE(s[2].at("modules")[0].at("ms_max").get<double>(), s[2].at("modules")[0].at("ms_mean").get<double>());
}

}  // namespace
}  // namespace nao
