// nao-soccer batch: an evaluation split into chunks of seeds on a runner (apps/Batch.h).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "apps/Batch.h"
#include "apps/Cli.h"
#include "apps/Commands.h"
#include "robot/Error.h"
#include "scenarios/EvalRows.h"

namespace nao::cli {

namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t interrupted = 0;
void onSignal(int) { interrupted = 1; }

// SIGINT, SIGTERM and SIGHUP stop the tasks instead of the process while a round runs.
class InterruptGuard {
 public:
  InterruptGuard() {
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &sa, &old_[i]);
  }
  ~InterruptGuard() {
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &old_[i], nullptr);
  }

 private:
  static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[3];
};

// The evaluation's seeds, as it would run them alone.
std::vector<std::uint64_t> evalSeeds(const std::string& path, Options& o) {
  if (path == "eval challenge") return sim::trialSeeds(o.evalChallenge.common.seed, o.evalChallenge.trials, o.evalChallenge.seeds, "--trials");
  if (path == "eval match") return sim::trialSeeds(o.evalMatch.common.seed, o.evalMatch.games, o.evalMatch.seeds, "--games");
  if (path == "eval calibration")
    return sim::trialSeeds(o.evalCalibration.common.seed, o.evalCalibration.trials, o.evalCalibration.seeds, "--trials");
  return sim::trialSeeds(o.evalLocalization.common.seed, o.evalLocalization.trials, o.evalLocalization.seeds, "--trials");
}

std::string chunkName(std::size_t k) {
  char name[32];
  std::snprintf(name, sizeof name, "chunk-%04zu", k);
  return name;
}

std::string lastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last.empty() ? "(empty)" : last;
}

std::string minutes(double s) {
  char buf[32];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  return buf;
}

}  // namespace

int batchCommand(const BatchOptions& options) {
  const auto wallStart = std::chrono::steady_clock::now();
  // The evaluation, parsed as it would be alone (the declarations checked it already).
  CommandLine inner;
  std::vector<const char*> argv{"nao-soccer"};
  for (const auto& a : options.evalArgs) argv.push_back(a.c_str());
  std::string help;
  const Command* evalCommand = inner.parse(static_cast<int>(argv.size()), argv.data(), help);
  BatchPlan plan;
  plan.eval = evalCommand->path();
  plan.evalArgs.assign(options.evalArgs.begin() + 2, options.evalArgs.end());
  plan.seeds = evalSeeds(plan.eval, inner.options());
  const std::string target = plan.eval.substr(plan.eval.find(' ') + 1);
  plan.chunkSize = options.chunk > 0 ? options.chunk : target == "localization" ? 4 : 1;

  const fs::path dir = fs::absolute(options.dir.empty() ? "batch-" + target : options.dir);
  const fs::path planFile = dir / "batch.json";
  const int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::unique_ptr<BatchRunner> runner;
  // A new batch checks its runner first: a Slurm that is not there leaves no folder behind.
  if (!options.resume && !fs::exists(planFile)) runner = makeBatchRunner(options.runner, jobs, options.sshlogin, dir.string());
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RunFailure(dir.string(), "cannot be made (" + ec.message() + ")");
  // The lock goes to the tasks too (inherited), so that a batch's leftover processes keep it.
  const int lock = ::open((dir / "lock").c_str(), O_RDWR | O_CREAT, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX | LOCK_NB) != 0)
    throw Error("--dir", dir.string() + " is in use by another batch or by tasks a batch left running");

  if (fs::exists(planFile)) {
    if (!options.resume)
      throw Error("--dir", dir.string() + " holds a batch already: --resume continues it, or give another --dir");
    std::ifstream in(planFile);
    const auto j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded()) throw Error(planFile.string(), "not JSON");
    const BatchPlan saved = BatchPlan::fromJson(j, planFile.string());
    if (saved.eval != plan.eval || saved.evalArgs != plan.evalArgs || saved.seeds != plan.seeds)
      throw Error("--resume", dir.string() + " holds another batch: " + saved.toJson().dump() + ", this one " +
                                  plan.toJson().dump());
    if (options.chunk > 0 && options.chunk != saved.chunkSize)
      throw Error("--chunk", dir.string() + "'s batch has " + std::to_string(saved.chunkSize) + " seeds per chunk");
    plan.chunkSize = saved.chunkSize;
  } else {
    if (options.resume) throw Error("--resume", dir.string() + " holds no batch to resume");
    std::ofstream out(planFile);
    out << plan.toJson().dump(2) << '\n';
    if (!out) throw RunFailure(planFile.string(), "cannot be written");
  }

  const auto chunks = plan.chunks();
  const auto rowsFile = [&](std::size_t k) { return (dir / (chunkName(k) + ".jsonl")).string(); };
  const auto logFile = [&](std::size_t k) { return (dir / (chunkName(k) + ".log")).string(); };
  const auto missingSeeds = [&](std::size_t k) { return readChunkRows(rowsFile(k), chunks[k]).missing.size(); };
  // Every chunk file is read before anything runs: a bad one stops the batch here.
  const auto countDone = [&] {
    std::size_t n = 0;
    for (std::size_t k = 0; k < chunks.size(); ++k) n += chunks[k].size() - missingSeeds(k);
    return n;
  };
  std::size_t done = countDone();
  std::size_t printed = done;  // the count of the last progress line
  const std::size_t total = plan.seeds.size(), doneBefore = done;

  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  int tasksRun = 0, tasksRerun = 0;
  for (int round = 1; round <= 2; ++round) {
    std::vector<BatchTask> tasks;
    for (std::size_t k = 0; k < chunks.size(); ++k) {
      if (missingSeeds(k) == 0) continue;
      BatchTask t;
      t.chunk = k;
      t.argv = {exe, "eval", target};
      t.argv.insert(t.argv.end(), plan.evalArgs.begin(), plan.evalArgs.end());
      // The chunk's seeds replace the evaluation's own count and first seed.
      for (std::size_t i = 0; i < t.argv.size(); ++i)
        if (t.argv[i] == "--seed" || t.argv[i] == "--trials" || t.argv[i] == "--games" || t.argv[i] == "--seeds") {
          t.argv.erase(t.argv.begin() + static_cast<long>(i), t.argv.begin() + static_cast<long>(std::min(i + 2, t.argv.size())));
          --i;
        } else if (t.argv[i].rfind("--seed=", 0) == 0 || t.argv[i].rfind("--trials=", 0) == 0 ||
                   t.argv[i].rfind("--games=", 0) == 0 || t.argv[i].rfind("--seeds=", 0) == 0) {
          t.argv.erase(t.argv.begin() + static_cast<long>(i));
          --i;
        }
      t.argv.insert(t.argv.end(), {"--seeds", seedListText(chunks[k]), "--rows", rowsFile(k)});
      t.log = logFile(k);
      tasks.push_back(std::move(t));
    }
    if (tasks.empty()) break;
    if (!runner) runner = makeBatchRunner(options.runner, jobs, options.sshlogin, dir.string());
    (round == 1 ? tasksRun : tasksRerun) += static_cast<int>(tasks.size());
    {
      InterruptGuard guard;
      interrupted = 0;
      runner->start(tasks);
      std::fprintf(stderr, "batch: %s, %zu seeds in %zu chunks, %zu with rows; %s %zu tasks on %s (%s)\n", plan.eval.c_str(),
                   total, chunks.size(), done, round == 1 ? "running" : "running again", tasks.size(), options.runner.c_str(),
                   dir.c_str());
      const auto roundStart = std::chrono::steady_clock::now();
      const std::size_t roundBefore = done;
      auto lastPrint = roundStart;
      printed = done;
      while (runner->busy()) {
        if (interrupted) {
          std::fprintf(stderr, "batch: interrupted: stopping the tasks\n");
          runner->cancel();
          done = countDone();
          throw RunFailure("", "interrupted with " + std::to_string(done) + " of " + std::to_string(total) +
                                        " seeds done; --resume runs the others");
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        const auto now = std::chrono::steady_clock::now();
        if (now - lastPrint < std::chrono::seconds(5)) continue;
        done = countDone();
        if (done == printed && now - lastPrint < std::chrono::seconds(60)) continue;
        const double elapsed = std::chrono::duration<double>(now - roundStart).count();
        const std::size_t newRows = done - roundBefore;
        std::string eta = newRows > 0 ? ", about " + minutes(elapsed / static_cast<double>(newRows) * static_cast<double>(total - done)) + " left" : "";
        std::fprintf(stderr, "batch: %zu/%zu seeds done%s\n", done, total, eta.c_str());
        printed = done;
        lastPrint = now;
      }
    }
    const auto statuses = runner->exitStatuses();
    std::vector<std::size_t> failed;
    done = countDone();
    // The round's last count, however short the round was.
    if (done != printed) std::fprintf(stderr, "batch: %zu/%zu seeds done\n", done, total);
    for (const auto& t : tasks) {
      const auto missing = readChunkRows(rowsFile(t.chunk), chunks[t.chunk]).missing;
      if (missing.empty()) continue;
      failed.push_back(t.chunk);
      const auto status = statuses.find(t.chunk);
      std::fprintf(stderr, "batch: %s (seeds %s) failed%s: seeds %s without a row; its log ends: %s\n",
                   chunkName(t.chunk).c_str(), seedListText(chunks[t.chunk]).c_str(),
                   status == statuses.end() ? "" : (" with exit " + std::to_string(status->second)).c_str(),
                   seedListText(missing).c_str(), escapeControl(lastLine(t.log)).c_str());
    }
    if (failed.empty()) break;
    if (round == 2) {
      std::vector<std::uint64_t> missing;
      for (const auto k : failed)
        for (const auto s : readChunkRows(rowsFile(k), chunks[k]).missing) missing.push_back(s);
      throw RunFailure("", std::to_string(failed.size()) + " chunk(s) failed twice: seeds " + seedListText(missing) +
                                    " have no row (" + logFile(failed.front()) + ")");
    }
  }

  // The merge: every row, sorted by seed, aggregated by the evaluation itself with nothing to run.
  std::map<std::uint64_t, nlohmann::json> all;
  const nlohmann::json* settings = nullptr;
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    ChunkRows c = readChunkRows(rowsFile(k), chunks[k]);
    for (auto& [seed, row] : c.rows) {
      if (!settings) settings = &all.emplace(seed, row).first->second.at("settings");
      else if (row.at("settings") != *settings)
        throw Error(rowsFile(k), "seed " + std::to_string(seed) + " was run with other settings than the batch's first row");
      all.emplace(seed, std::move(row));
    }
  }
  const fs::path merged = dir / "rows.jsonl", aggregateFile = dir / "aggregate.json", mergeLog = dir / "merge.log";
  {
    std::ofstream out(merged.string() + ".tmp", std::ios::trunc);
    for (const auto& [seed, row] : all) out << row.dump() << '\n';
    out.close();
    if (!out) throw RunFailure(merged.string(), "cannot be written");
    fs::rename(merged.string() + ".tmp", merged);
  }
  fs::remove(aggregateFile, ec);
  std::string mergeCommand = shellQuote(exe) + " eval " + target;
  for (const auto& a : plan.evalArgs) mergeCommand += " " + shellQuote(a);
  mergeCommand += " --rows " + shellQuote(merged.string()) + " --json " + shellQuote(aggregateFile.string()) + " >" +
                  shellQuote(mergeLog.string()) + " 2>&1 </dev/null";
  const int rc = std::system(mergeCommand.c_str());
  if (rc != 0 || !fs::exists(aggregateFile))
    throw RunFailure("", "the merge (eval " + target + " --rows " + merged.string() + ") failed: " +
                                  escapeControl(lastLine(mergeLog.string())));
  std::ifstream in(aggregateFile);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object()) throw RunFailure(aggregateFile.string(), "the merge wrote no JSON object");
  j["runner"] = options.runner;
  j["chunks"] = chunks.size();
  j["seeds"] = plan.seeds;  // eval localization's own key says the same
  j["batch"] = {{"dir", dir.string()},
                {"eval", plan.eval},
                {"seed_count", total},
                {"seeds_done_before", doneBefore},
                {"tasks_run", tasksRun},
                {"tasks_rerun", tasksRerun},
                {"wall_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count()}};
  std::fprintf(stderr, "batch: %zu seeds merged from %zu chunks (%d tasks run, %d again; %zu seeds were done before)\n",
               total, chunks.size(), tasksRun, tasksRerun, doneBefore);
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  ::close(lock);
  return 0;
}

}  // namespace nao::cli
