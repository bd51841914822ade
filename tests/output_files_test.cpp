// robot/OutputFiles.h: complete files or none, checked writes, a failed run leaves nothing.
#include "robot/OutputFiles.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>

#include "robot/Error.h"

namespace {

namespace fs = std::filesystem;
using nao::io::OutputTransaction;

std::string freshDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("output_files_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::size_t entries(const std::string& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputFiles, WritesAndReplacesWithoutATransaction) {
  const std::string dir = freshDir("plain"), path = dir + "/a.json";
  nao::io::writeFile(path, "first");
  EXPECT_EQ(slurp(path), "first");
  nao::io::writeFile(path, "second");
  EXPECT_EQ(slurp(path), "second");
  EXPECT_EQ(entries(dir), 1u);  // no temporary left beside it
}

TEST(OutputFiles, TransactionShowsFilesOnlyOnCommit) {
  const std::string dir = freshDir("commit"), path = dir + "/img/a.png";
  {
    OutputTransaction t;
    nao::io::makeDirectories(dir + "/img");
    nao::io::writeFile(path, "picture");
    nao::io::writeFile(path, "picture 2");  // written twice in one run: the newer wins
    EXPECT_FALSE(fs::exists(path));
    t.commit();
  }
  EXPECT_EQ(slurp(path), "picture 2");
  EXPECT_EQ(entries(dir + "/img"), 1u);
}

TEST(OutputFiles, DiscardedTransactionLeavesNothing) {
  const std::string dir = freshDir("discard");
  std::ofstream(dir + "/kept.txt") << "from before";
  {
    OutputTransaction t;
    nao::io::makeDirectories(dir + "/new/deeper");
    nao::io::writeFile(dir + "/new/deeper/a.png", "picture");
    nao::io::writeFile(dir + "/kept.txt", "would replace");
    nao::io::writeFileWith(dir + "/model.yml", [](const std::string& temp) { std::ofstream(temp) << "weights"; });
  }  // no commit: the run failed
  EXPECT_FALSE(fs::exists(dir + "/new"));
  EXPECT_FALSE(fs::exists(dir + "/model.yml"));
  EXPECT_EQ(slurp(dir + "/kept.txt"), "from before");
  EXPECT_EQ(entries(dir), 1u);
}

// Ctrl-C while a file is half written (in a child process, which dies of it): the temporary
// file goes with the folders the run made. Before the in-flight files were known to the
// handler, the temporary kept the folder from being removed (seen once in CI's Cli test).
TEST(OutputFiles, InterruptedMidWriteLeavesNothing) {
  const std::string dir = freshDir("interrupted");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputTransaction t;
    t.discardOnSignals();
    nao::io::makeDirectories(dir + "/run/images");
    nao::io::writeFile(dir + "/run/images/done.png", "staged");
    nao::io::writeFileWith(dir + "/run/images/half.png", [](const std::string& temp) {
      std::ofstream(temp) << "half a picture";
      std::raise(SIGINT);
    });
    ::_exit(0);  // not reached: the signal ends the child
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child was not ended by the signal";
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_FALSE(fs::exists(dir + "/run")) << "left: " << (fs::exists(dir + "/run/images") ? "images" : "run");
  EXPECT_EQ(entries(dir), 0u);
}

TEST(OutputFiles, WriterThatWritesNothingFails) {
  const std::string dir = freshDir("nothing");
  EXPECT_THROW(nao::io::writeFileWith(dir + "/m.yml", [](const std::string&) {}), nao::RunFailure);
  EXPECT_EQ(entries(dir), 0u);
}

TEST(OutputFiles, FullDiskIsAFailureNamingThePath) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  try {
    nao::io::writeFile("/dev/full", std::string(4096, 'x'));
    FAIL() << "a write to /dev/full succeeded";
  } catch (const nao::RunFailure& e) {
    EXPECT_EQ(e.where(), "/dev/full");
    EXPECT_NE(std::string(e.what()).find("write failed"), std::string::npos) << e.what();
  }
  // A device is written in place, never replaced by a renamed file.
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputFiles, ProblemsFoundBeforeARun) {
  const std::string dir = freshDir("checks");
  std::ofstream(dir + "/file") << "x";
  EXPECT_EQ(nao::io::outputFileProblem(dir + "/ok.json"), "");
  EXPECT_EQ(nao::io::outputFileProblem(dir + "/file"), "");  // replaced
  EXPECT_NE(nao::io::outputFileProblem(""), "");
  EXPECT_NE(nao::io::outputFileProblem(dir).find("folder"), std::string::npos);
  EXPECT_NE(nao::io::outputFileProblem(dir + "/missing/x.json").find("does not exist"), std::string::npos);
  EXPECT_NE(nao::io::outputFileProblem(dir + "/" + std::string(300, 'a')).find("too long"), std::string::npos);
  EXPECT_EQ(nao::io::outputDirectoryProblem(dir + "/new/deeper"), "");  // made when needed
  EXPECT_NE(nao::io::outputDirectoryProblem(dir + "/file/sub").find("not a folder"), std::string::npos);
  EXPECT_NE(nao::io::outputDirectoryProblem(""), "");
}

}  // namespace
