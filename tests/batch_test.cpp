// nao-soccer batch (apps/Batch.h): the same aggregate as one uninterrupted evaluation on every
// runner (processes here, GNU parallel, a real single-node Slurm from tools/slurm-local.sh), a
// Slurm run killed half-way resumed with only its missing seeds, a crashed task rerun once, and
// bad input refused with one line. The evaluation is eval localization with 5 s walks in the fast
// percept mode (the robot program's own localization, its percepts from OracleVision): a second
// or two a trial, and an aggregate of many figures.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/Batch.h"
#include "robot/Error.h"
#include "support/JsonTimes.h"
#include "support/RunCommand.h"

namespace {

namespace fs = std::filesystem;
using nao::cli::BatchPlan;
using nao::cli::readChunkRows;
using nao::cli::seedListText;
using nao::test::runCommand;

const std::string kEval =
    "eval localization --seconds 5 --kidnap-every 0 --roll-every 0 --lighting sweep --percepts oracle";

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("batch_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

nlohmann::json readJson(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in, nullptr, false);
}

// The aggregate without batch's own keys (and the seed list, which eval localization has too).
nlohmann::json result(nlohmann::json j) {
  for (const char* k : {"runner", "chunks", "seeds", "batch"}) j.erase(k);
  return j;
}

// Runs a shell command line; stdout and stderr together.
nao::test::CommandResult shell(const std::string& cmd, int timeoutSeconds = 120) {
  nao::test::CommandResult r;
  FILE* p = popen(("timeout -s KILL " + std::to_string(timeoutSeconds) + " sh -c " + nao::cli::shellQuote(cmd) + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::size_t lines(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  std::string l;
  while (std::getline(in, l)) n += !l.empty();
  return n;
}

// The rows of a batch folder by seed, counted over every chunk file.
std::map<std::uint64_t, int> seedCounts(const fs::path& dir) {
  std::map<std::uint64_t, int> counts;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("chunk-", 0) != 0 || e.path().extension() != ".jsonl") continue;
    std::ifstream in(e.path());
    std::string l;
    while (std::getline(in, l)) {
      const auto j = nlohmann::json::parse(l, nullptr, false);
      if (j.is_object() && j.contains("seed")) ++counts[j["seed"].get<std::uint64_t>()];
    }
  }
  return counts;
}

// ---------------------------------------------------------------------------------------------
// The plan and the chunk files, without running anything.

TEST(BatchPlan, ChunksCoverTheSeedsInOrderAndTheFileRoundTrips) {
  BatchPlan p;
  p.eval = "eval challenge";
  p.evalArgs = {"--randomize", "--lighting", "sweep"};
  p.seeds = {5, 6, 7, 8, 9, 20, 21};
  p.chunkSize = 3;
  const auto c = p.chunks();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], (std::vector<std::uint64_t>{5, 6, 7}));
  EXPECT_EQ(c[2], (std::vector<std::uint64_t>{21}));
  EXPECT_EQ(seedListText(p.seeds), "5-9,20-21");
  EXPECT_EQ(seedListText({3, 1, 2}), "3,1-2");
  const BatchPlan q = BatchPlan::fromJson(p.toJson(), "batch.json");
  EXPECT_EQ(q.seeds, p.seeds);
  EXPECT_EQ(q.evalArgs, p.evalArgs);
  EXPECT_EQ(q.chunkSize, 3);
  nlohmann::json bad = p.toJson();
  bad["seeds"] = "5-x";
  EXPECT_THROW(BatchPlan::fromJson(bad, "batch.json"), nao::Error);
  bad = p.toJson();
  bad.erase("chunk");
  EXPECT_THROW(BatchPlan::fromJson(bad, "batch.json"), nao::Error);
}

TEST(BatchChunkRows, ACutShortLastLineIsMissingAnythingElseBadIsRefused) {
  const fs::path d = tempDir("rows");
  const std::string row1 = R"({"seed":1,"settings":{"a":1},"x":0.5})", row2 = R"({"seed":2,"settings":{"a":1}})";
  const auto write = [&](const std::string& text) {
    std::ofstream(d / "c.jsonl", std::ios::binary) << text;
    return (d / "c.jsonl").string();
  };
  auto r = readChunkRows(write(row1 + "\n" + row2.substr(0, 10)), {1, 2, 3});
  EXPECT_EQ(r.rows.size(), 1u);
  EXPECT_TRUE(r.truncatedTail);
  EXPECT_EQ(r.missing, (std::vector<std::uint64_t>{2, 3}));
  r = readChunkRows(write(row1 + "\n" + row2), {1, 2});  // complete, only its newline missing
  EXPECT_TRUE(r.missing.empty());
  r = readChunkRows((d / "none.jsonl").string(), {4, 5});
  EXPECT_EQ(r.missing.size(), 2u);
  const auto refused = [&](const std::string& text, const std::string& what) {
    try {
      readChunkRows(write(text), {1, 2});
      ADD_FAILURE() << "accepted: " << text;
    } catch (const nao::Error& e) {
      EXPECT_NE(std::string(e.what()).find("c.jsonl"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused(row1.substr(0, 12) + "\n" + row2 + "\n", "line 1: not a row");
  refused(row1 + "\n" + row1 + "\n", "line 2: seed 1 has a second row");
  refused(R"({"seed":9,"settings":{}})" "\n", "seed 9 is not one of this chunk's");
  refused("[1,2]\n" + row2 + "\n", "line 1");
  refused(R"({"seed":-1,"settings":{}})" "\n", "line 1");
}

// ---------------------------------------------------------------------------------------------
// The runners, on real evaluations.

class BatchRunners : public ::testing::Test {
 protected:
  // One single-node Slurm for the suite, on ports and in a folder of its own: ctest runs each
  // test in a process of its own, several at once, and each starts its own Slurm.
  static void SetUpTestSuite() {
    slurmDir_ = tempDir("slurm_" + std::to_string(::getpid()));
    if (::geteuid() != 0) {
      why_ = "the single-node Slurm needs root";
      return;
    }
    const std::string env = "NAO_SLURM_DIR=" + slurmDir_.string() + " NAO_SLURM_PORT=" + std::to_string(20000 + (::getpid() % 10000) * 2);
    const std::string cmd = env + " " + NAO_SOURCE_DIR + "/tools/slurm-local.sh start > " + (slurmDir_ / "env").string() + " 2>&1";
    if (std::system(cmd.c_str()) != 0) {
      std::ifstream in(slurmDir_ / "env");
      why_ = "tools/slurm-local.sh start failed: " + std::string(std::istreambuf_iterator<char>(in), {});
      return;
    }
    started_ = true;
    ::setenv("SLURM_CONF", (slurmDir_ / "slurm.conf").c_str(), 1);
  }
  static void TearDownTestSuite() {
    if (!started_) return;
    const std::string cmd = "NAO_SLURM_DIR=" + slurmDir_.string() + " " + NAO_SOURCE_DIR + "/tools/slurm-local.sh stop 2>/dev/null";
    (void)std::system(cmd.c_str());
    fs::remove_all(slurmDir_);
  }
  // Skips without a Slurm here, but fails in CI, which installs one (.ci/install-deps.sh).
  static bool needSlurm() {
    if (started_) return true;
    if (std::getenv("CI")) ADD_FAILURE() << why_;
    else GTEST_LOG_(INFO) << "skipped: " << why_;
    return false;
  }
  static inline fs::path slurmDir_;
  static inline bool started_ = false;
  static inline std::string why_;
};

TEST_F(BatchRunners, EveryRunnerGivesTheAggregateOfOneUninterruptedRun) {
  const fs::path d = tempDir("runners");
  const int trials = std::getenv("NAO_TEST_QUICK") ? 2 : 3;
  const std::string eval = kEval + " --seed 3 --trials " + std::to_string(trials);
  auto r = runCommand(eval + " --json " + (d / "single.json").string(), 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json single = readJson(d / "single.json");
  ASSERT_TRUE(single.contains("position_error_m"));
  ASSERT_EQ(single["trials"], trials);
  ASSERT_EQ(single["settings"]["percepts"], "oracle");

  struct Case {
    std::string runner;
    int chunk;
  };
  std::vector<Case> cases = {{"local", 1}, {"parallel", 3}};
  if (needSlurm()) cases.push_back({"slurm", 2});
  for (const auto& c : cases) {
    const fs::path dir = d / c.runner;
    r = runCommand("batch " + eval + " --runner " + c.runner + " --chunk " + std::to_string(c.chunk) + " --dir " +
                       dir.string() + " --json " + (d / (c.runner + ".json")).string(),
                   600);
    ASSERT_EQ(r.code, 0) << c.runner << ":\n" << r.out;
    const nlohmann::json j = readJson(d / (c.runner + ".json"));
    EXPECT_EQ(j["runner"], c.runner);
    std::vector<std::uint64_t> seeds;
    for (int i = 0; i < trials; ++i) seeds.push_back(3 + static_cast<std::uint64_t>(i));
    EXPECT_EQ(j["seeds"], seeds);
    EXPECT_EQ(j["batch"]["seed_count"], trials);
    EXPECT_EQ(j["chunks"], (trials + c.chunk - 1) / c.chunk);
    EXPECT_EQ(result(j), result(single)) << c.runner << " differs from one uninterrupted run";
    // Every seed ran exactly once, each in its chunk.
    const auto counts = seedCounts(dir);
    EXPECT_EQ(counts.size(), static_cast<std::size_t>(trials));
    for (const auto& [seed, n] : counts) EXPECT_EQ(n, 1) << c.runner << " seed " << seed;
    EXPECT_NE(r.out.find("seeds done"), std::string::npos) << "no progress on stderr:\n" << r.out;
  }
}

// eval calibration split into chunks of one trial each: its own aggregate, each trial once.
// (2 s phases: a trial is a walk towards the goal box, no sample.)
TEST(BatchCalibration, ChunksGiveTheAggregateOfOneRun) {
  const fs::path d = tempDir("calibration");
  const std::string eval = "eval calibration --seed 5 --trials 2 --time-limit 2 --lighting default";
  auto r = runCommand(eval + " --json " + (d / "single.json").string(), 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json single = readJson(d / "single.json");
  ASSERT_EQ(single["trials"], 2);
  r = runCommand("batch " + eval + " --runner local --jobs 2 --chunk 1 --dir " + (d / "b").string() + " --json " +
                     (d / "batch.json").string(),
                 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = readJson(d / "batch.json");
  EXPECT_EQ(j["seeds"], (std::vector<std::uint64_t>{5, 6}));
  EXPECT_EQ(j["chunks"], 2);
  EXPECT_EQ(nao::test::withoutTimes(result(j)), nao::test::withoutTimes(single));
  const auto counts = seedCounts(d / "b");
  EXPECT_EQ(counts, (std::map<std::uint64_t, int>{{5, 1}, {6, 1}}));
}

TEST_F(BatchRunners, SlurmKilledHalfWayResumesOnlyTheMissingSeeds) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "Slurm's scheduling under the sanitizers: the Release stage runs it";
  if (!needSlurm()) return;
  const fs::path d = tempDir("resume");
  const std::string eval = kEval + " --seed 11 --trials 6";
  const std::string batch = std::string(NAO_BINARY) + " batch " + eval + " --runner slurm --chunk 1 --dir " + (d / "b").string();
  // Started in the background; stopped with SIGTERM once two seeds have rows.
  const std::string start = batch + " > " + (d / "first.log").string() + " 2>&1 & echo $!";
  FILE* p = popen(start.c_str(), "r");
  ASSERT_NE(p, nullptr);
  int pid = 0;
  ASSERT_EQ(std::fscanf(p, "%d", &pid), 1);
  pclose(p);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    std::size_t rows = 0;
    if (fs::exists(d / "b"))
      for (const auto& [seed, n] : seedCounts(d / "b")) rows += n;
    if (rows >= 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  for (int i = 0; i < 600 && ::kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::ifstream firstLog(d / "first.log");
  const std::string first(std::istreambuf_iterator<char>(firstLog), {});
  EXPECT_NE(first.find("--resume runs the others"), std::string::npos) << first;
  const auto queue = shell("squeue -h -o %i");
  EXPECT_EQ(queue.code, 0) << queue.out;
  EXPECT_TRUE(queue.out.empty()) << "jobs left in Slurm after the interrupt:\n" << queue.out;
  const auto before = seedCounts(d / "b");
  ASSERT_GE(before.size(), 2u);
  ASSERT_LT(before.size(), 6u) << "the batch ended before it was killed";
  EXPECT_FALSE(fs::exists(d / "b" / "aggregate.json"));

  // Without --resume the folder is refused; with it only the missing seeds run.
  auto r = runCommand("batch " + eval + " --runner slurm --chunk 1 --dir " + (d / "b").string(), 60);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--resume"), std::string::npos) << r.out;
  r = runCommand("batch " + eval + " --runner slurm --resume --dir " + (d / "b").string() + " --json " +
                     (d / "resumed.json").string(),
                 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = readJson(d / "resumed.json");
  EXPECT_EQ(j["batch"]["seeds_done_before"], before.size());
  EXPECT_EQ(j["batch"]["tasks_run"], 6 - static_cast<int>(before.size()));
  const auto after = seedCounts(d / "b");
  EXPECT_EQ(after.size(), 6u);
  for (const auto& [seed, n] : after) EXPECT_EQ(n, 1) << "seed " << seed << " ran twice";
  for (const auto& [seed, n] : before) {
    (void)n;
    EXPECT_EQ(after.count(seed), 1u);
  }
  // The same aggregate as the evaluation alone gives.
  r = runCommand(eval + " --json " + (d / "single.json").string(), 600);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(result(j), result(readJson(d / "single.json")));
}

TEST_F(BatchRunners, ACrashedTaskIsReportedWithItsSeedsAndRunAgainOnce) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a whole batch: the Release stage runs it";
  const fs::path d = tempDir("crash");
  const std::string eval = kEval + " --seed 21 --trials 3";
  const std::string start = std::string(NAO_BINARY) + " batch " + eval + " --runner local --jobs 1 --chunk 1 --dir " +
                            (d / "b").string() + " --json " + (d / "b.json").string() + " > " + (d / "log").string() +
                            " 2>&1 & echo $!";
  FILE* p = popen(start.c_str(), "r");
  ASSERT_NE(p, nullptr);
  int pid = 0;
  ASSERT_EQ(std::fscanf(p, "%d", &pid), 1);
  pclose(p);
  // The second chunk's task is killed as soon as it runs: a crash.
  // (The pattern's [1] keeps pgrep's own shell, whose line holds the pattern, from matching.)
  const std::string find = "pgrep -f -- '--rows " + (d / "b").string() + "/chunk-000[1]'";
  int victim = 0;
  for (int i = 0; i < 3000 && victim == 0; ++i) {
    const auto found = shell(find);
    victim = found.code == 0 ? std::atoi(found.out.c_str()) : 0;
    if (victim == 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_NE(victim, 0) << "the second task never ran";
  ::kill(victim, SIGKILL);
  for (int i = 0; i < 3000 && ::kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::ifstream in(d / "log");
  const std::string log(std::istreambuf_iterator<char>(in), {});
  EXPECT_NE(log.find("chunk-0001 (seeds 22) failed with exit 137: seeds 22 without a row"), std::string::npos) << log;
  EXPECT_NE(log.find("running again 1 tasks"), std::string::npos) << log;
  const nlohmann::json j = readJson(d / "b.json");
  ASSERT_TRUE(j.is_object()) << log;
  EXPECT_EQ(j["batch"]["tasks_rerun"], 1);
  EXPECT_EQ(j["trials"], 3);
  for (const auto& [seed, n] : seedCounts(d / "b")) EXPECT_EQ(n, 1) << "seed " << seed;
}

// ---------------------------------------------------------------------------------------------
// Bad input: one line naming what failed, nothing merged from a bad file.

bool oneLine(const std::string& out) {
  std::size_t n = 0;
  for (char c : out) n += c == '\n';
  return n == 1 && out.rfind("nao-soccer batch", 0) == 0;
}

TEST(BatchInput, RefusedBeforeAnythingRuns) {
  const fs::path d = tempDir("input");
  const std::string dir = " --dir " + (d / "b").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"batch " + kEval + " --runner condor" + dir, "--runner"},
      {"batch " + kEval + " --seeds 1,2,1" + dir, "--seeds"},
      {"batch " + kEval + " --seeds 1-3,2" + dir, "seed 2 is listed twice"},
      {"batch " + kEval + " --rows x.jsonl" + dir, "--rows"},
      {"batch " + kEval + " --trials 0" + dir, "--trials"},
      {"batch eval perception --trials 2" + dir, "eval perception"},
      {"batch" + dir, "needs the evaluation"},
      {"batch walk" + dir, "walk"},
      {"batch --frobnicate" + dir, "--frobnicate"},
      {"batch " + kEval + " --sshlogin host1 --runner local" + dir, "--sshlogin"},
      {"batch " + kEval + " --resume" + dir, "no batch to resume"},
  };
  for (const auto& [args, name] : cases) {
    const auto r = runCommand(args, 60);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
    EXPECT_TRUE(oneLine(r.out)) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(name), std::string::npos) << args << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(d / "b" / "chunk-0000.jsonl"));
}

TEST(BatchInput, SlurmMissingOrRefusingIsARunFailureNamingIt) {
  const fs::path d = tempDir("slurm_input");
  const std::string eval = "batch " + kEval + " --trials 2 --runner slurm --dir " + (d / "b").string();
  const auto run = [&](const std::string& env) { return shell("env " + env + " " + NAO_BINARY + " " + eval, 90); };

  // No configuration file.
  auto r = run("SLURM_CONF=" + (d / "none.conf").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_TRUE(oneLine(r.out)) << r.out;
  EXPECT_NE(r.out.find("--runner slurm: no Slurm configuration"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "b")) << "a refused batch left its folder";
  // A configuration whose controller is not running (a port nobody listens on).
  std::ofstream(d / "dead.conf") << "ClusterName=dead\nSlurmctldHost=localhost\nSlurmctldPort=1\nAuthType=auth/munge\n"
                                    "NodeName=localhost CPUs=1\nPartitionName=p Nodes=localhost Default=YES\n";
  r = run("SLURM_CONF=" + (d / "dead.conf").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_TRUE(oneLine(r.out)) << r.out;
  EXPECT_NE(r.out.find("--runner slurm"), std::string::npos) << r.out;
}

TEST_F(BatchRunners, SlurmRefusingTheJobIsARunFailureNamingIt) {
  if (!needSlurm()) return;
  const fs::path d = tempDir("refused");
  // sbatch takes its partition from SBATCH_PARTITION: one that does not exist is refused.
  const auto r = shell("SBATCH_PARTITION=nosuch " + std::string(NAO_BINARY) + " batch " + kEval +
                       " --trials 2 --runner slurm --dir " + (d / "b").string());
  const std::string& out = r.out;
  EXPECT_EQ(r.code, 1) << out;
  EXPECT_TRUE(oneLine(out)) << out;
  EXPECT_NE(out.find("sbatch refused the job array"), std::string::npos) << out;
  EXPECT_NE(out.find("nosuch"), std::string::npos) << out;
}

TEST(BatchInput, ABadChunkFileIsNeverMergedAndACutShortRowRunsAgain) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a whole batch: the Release stage runs it";
  const fs::path d = tempDir("corrupt");
  const std::string eval = kEval + " --seed 31 --trials 2";
  const std::string batch = "batch " + eval + " --runner local --chunk 2 --dir " + (d / "b").string();
  auto r = runCommand(batch + " --json " + (d / "first.json").string(), 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const fs::path chunk = d / "b" / "chunk-0000.jsonl";
  std::ifstream in(chunk);
  std::string row1, row2;
  std::getline(in, row1);
  std::getline(in, row2);
  in.close();
  ASSERT_FALSE(row2.empty());
  fs::remove(d / "b" / "aggregate.json");

  // The second row cut short (a task stopped while writing it): --resume runs seed 32 again.
  std::ofstream(chunk, std::ios::trunc) << row1 << "\n" << row2.substr(0, row2.size() / 2);
  r = runCommand(batch + " --resume --json " + (d / "again.json").string(), 600);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(lines(chunk), 2u);
  EXPECT_EQ(result(readJson(d / "again.json")), result(readJson(d / "first.json")));

  // A first line that is garbage: refused, naming the file and the line; nothing merged.
  fs::remove(d / "b" / "aggregate.json");
  std::ofstream(chunk, std::ios::trunc) << "{\"seed\": 31, garbage\n" << row2 << "\n";
  r = runCommand(batch + " --resume --json " + (d / "bad.json").string(), 60);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(oneLine(r.out)) << r.out;
  EXPECT_NE(r.out.find(chunk.string() + ": line 1: not a row"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "bad.json"));
  EXPECT_FALSE(fs::exists(d / "b" / "aggregate.json"));
  // A row twice.
  std::ofstream(chunk, std::ios::trunc) << row1 << "\n" << row1 << "\n";
  r = runCommand(batch + " --resume --json " + (d / "bad.json").string(), 60);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("seed 31 has a second row"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "bad.json"));
  // Another batch's folder.
  r = runCommand("batch " + kEval + " --seed 40 --trials 2 --runner local --resume --dir " + (d / "b").string(), 60);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("holds another batch"), std::string::npos) << r.out;
}

}  // namespace
