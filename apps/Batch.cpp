#include "apps/Batch.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <thread>

#include "robot/Error.h"

extern char** environ;

namespace nao::cli {

namespace fs = std::filesystem;

std::vector<std::vector<std::uint64_t>> BatchPlan::chunks() const {
  std::vector<std::vector<std::uint64_t>> out;
  const std::size_t size = static_cast<std::size_t>(std::max(1, chunkSize));
  for (std::size_t i = 0; i < seeds.size(); i += size)
    out.emplace_back(seeds.begin() + static_cast<long>(i), seeds.begin() + static_cast<long>(std::min(seeds.size(), i + size)));
  return out;
}

nlohmann::json BatchPlan::toJson() const {
  return {{"eval", eval}, {"eval_args", evalArgs}, {"seeds", seedListText(seeds)}, {"seed_count", seeds.size()},
          {"chunk", chunkSize}};
}

std::string seedListText(const std::vector<std::uint64_t>& seeds) {
  std::string s;
  for (std::size_t i = 0; i < seeds.size();) {
    std::size_t j = i;
    while (j + 1 < seeds.size() && seeds[j + 1] == seeds[j] + 1) ++j;
    if (!s.empty()) s += ',';
    s += std::to_string(seeds[i]);
    if (j > i) {
      s += '-';
      s += std::to_string(seeds[j]);
    }
    i = j + 1;
  }
  return s;
}

namespace {

// The inverse of seedListText, for a plan file (the command line's --seeds has its own parser).
std::vector<std::uint64_t> parseSeedList(const std::string& s, const std::string& path) {
  std::vector<std::uint64_t> seeds;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::uint64_t a = 0, b = 0;
    char tail = 0;
    if (std::sscanf(item.c_str(), "%lu-%lu%c", &a, &b, &tail) == 2 && b >= a && b - a < 10000000) {
      for (std::uint64_t v = a; v <= b; ++v) seeds.push_back(v);
    } else if (std::sscanf(item.c_str(), "%lu%c", &a, &tail) == 1) {
      seeds.push_back(a);
    } else {
      throw Error(path, "seeds: " + item + " is not a seed or a range");
    }
  }
  return seeds;
}

}  // namespace

BatchPlan BatchPlan::fromJson(const nlohmann::json& j, const std::string& path) {
  try {
    BatchPlan p;
    p.eval = j.at("eval").get<std::string>();
    p.evalArgs = j.at("eval_args").get<std::vector<std::string>>();
    p.seeds = parseSeedList(j.at("seeds").get<std::string>(), path);
    p.chunkSize = j.at("chunk").get<int>();
    if (p.chunkSize < 1) throw Error(path, "chunk: must be at least 1");
    if (p.seeds.size() != j.at("seed_count").get<std::size_t>()) throw Error(path, "seeds: not seed_count of them");
    return p;
  } catch (const nlohmann::json::exception& e) {
    throw Error(path, std::string("not a batch plan (") + e.what() + ")");
  }
}

ChunkRows readChunkRows(const std::string& path, const std::vector<std::uint64_t>& seeds) {
  ChunkRows out;
  const std::set<std::uint64_t> mine(seeds.begin(), seeds.end());
  std::error_code ec;
  if (fs::exists(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot be read");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::size_t pos = 0, line = 0;
    while (pos < text.size()) {
      ++line;
      const std::size_t end = text.find('\n', pos);
      const bool complete = end != std::string::npos;
      const std::string s = text.substr(pos, complete ? end - pos : std::string::npos);
      pos = complete ? end + 1 : text.size();
      const auto j = nlohmann::json::parse(s, nullptr, false);
      const bool isRow = !j.is_discarded() && j.is_object() && j.contains("settings") && j.contains("seed") &&
                         j.at("seed").is_number_unsigned();
      if (!complete && !isRow) {  // the eval cuts it off and runs its trial again
        out.truncatedTail = true;
        break;
      }
      const std::string where = "line " + std::to_string(line) + ": ";
      if (!isRow) throw Error(path, where + "not a row (a JSON object with seed and settings)");
      const auto seed = j.at("seed").get<std::uint64_t>();
      if (!mine.count(seed)) throw Error(path, where + "seed " + std::to_string(seed) + " is not one of this chunk's");
      if (out.rows.count(seed)) throw Error(path, where + "seed " + std::to_string(seed) + " has a second row");
      out.rows.emplace(seed, j);
    }
  }
  for (const auto s : seeds)
    if (!out.rows.count(s)) out.missing.push_back(s);
  return out;
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  q += '\'';
  return q;
}

namespace {

std::string commandLine(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) {
    if (!s.empty()) s += ' ';
    s += shellQuote(a);
  }
  return s;
}

// Starts argv (PATH searched) in a process group of its own, stdin from /dev/null, stdout and
// stderr appended to `log`. Throws RunFailure.
pid_t spawn(const std::vector<std::string>& argv, const std::string& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attr, 0);
  sigset_t all, none;
  sigfillset(&all);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &all);
  posix_spawnattr_setsigmask(&attr, &none);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) throw RunFailure(argv[0], std::string("cannot be started: ") + std::strerror(rc));
  return pid;
}

// The exit code of a wait status (128 + signal for a killed process).
int exitCode(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

// Runs argv to its end within `timeoutS`; its stdout and stderr together.
int runCaptured(const std::vector<std::string>& argv, std::string& output, double timeoutS = 60) {
  const fs::path tmp = fs::temp_directory_path() / ("nao-batch-" + std::to_string(::getpid()) + ".out");
  fs::remove(tmp);
  const pid_t pid = spawn(argv, tmp.string());
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutS);
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      fs::remove(tmp);
      output = argv[0] + " did not answer in " + std::to_string(static_cast<int>(timeoutS)) + " s";
      return 124;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::ifstream in(tmp);
  output.assign(std::istreambuf_iterator<char>(in), {});
  fs::remove(tmp);
  return exitCode(status);
}

std::string firstLine(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  return l.empty() ? "(no output)" : l;
}

// Stops a process group: TERM, then KILL after `graceS`; reaps `pid`.
void stopGroup(pid_t pid, double graceS) {
  ::kill(-pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(graceS);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(-pid, SIGKILL);  // what the leader left behind in its group
}

// Processes on this machine, `jobs` at once.
class LocalRunner : public BatchRunner {
 public:
  explicit LocalRunner(int jobs) : jobs_(jobs) {}
  void start(const std::vector<BatchTask>& tasks) override {
    waiting_.assign(tasks.begin(), tasks.end());
    fill();
  }
  bool busy() override {
    for (auto it = running_.begin(); it != running_.end();) {
      int status = 0;
      if (::waitpid(it->first, &status, WNOHANG) == it->first) {
        statuses_[it->second] = exitCode(status);
        ::kill(-it->first, SIGKILL);  // anything the task left in its group
        it = running_.erase(it);
      } else {
        ++it;
      }
    }
    fill();
    return !running_.empty() || !waiting_.empty();
  }
  void cancel() override {
    waiting_.clear();
    for (const auto& [pid, chunk] : running_) ::kill(-pid, SIGTERM);
    for (const auto& [pid, chunk] : running_) stopGroup(pid, 5);
    running_.clear();
  }
  std::map<std::size_t, int> exitStatuses() const override { return statuses_; }

 private:
  void fill() {
    while (static_cast<int>(running_.size()) < jobs_ && !waiting_.empty()) {
      const BatchTask t = waiting_.front();
      waiting_.pop_front();
      running_[spawn(t.argv, t.log)] = t.chunk;
    }
  }
  int jobs_;
  std::deque<BatchTask> waiting_;
  std::map<pid_t, std::size_t> running_;
  std::map<std::size_t, int> statuses_;
};

// GNU parallel, one task per line of a task file; its job log gives the exit statuses.
class ParallelRunner : public BatchRunner {
 public:
  ParallelRunner(int jobs, std::string sshlogin, std::string dir)
      : jobs_(jobs), sshlogin_(std::move(sshlogin)), dir_(std::move(dir)) {
    std::string out;
    if (runCaptured({"parallel", "--version"}, out, 20) != 0)
      throw RunFailure("--runner parallel", "GNU parallel does not run: " + firstLine(out) + " (apt-get install parallel)");
  }
  void start(const std::vector<BatchTask>& tasks) override {
    const std::string taskFile = dir_ + "/parallel-tasks.txt";
    std::ofstream f(taskFile, std::ios::trunc);
    for (const auto& t : tasks) {
      f << commandLine(t.argv) << " >> " << shellQuote(t.log) << " 2>&1\n";
      chunks_.push_back(t.chunk);
    }
    f.close();
    if (!f) throw RunFailure(taskFile, "cannot be written");
    joblog_ = dir_ + "/parallel.joblog";
    std::vector<std::string> argv = {"parallel", "--jobs", std::to_string(jobs_), "--joblog", joblog_, "--arg-file", taskFile};
    if (!sshlogin_.empty()) {
      argv.insert(argv.begin() + 1, {"--sshlogin", sshlogin_, "--workdir", "."});
    }
    pid_ = spawn(argv, dir_ + "/parallel.log");
  }
  bool busy() override {
    if (pid_ <= 0) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) != pid_) return true;
    pid_ = -1;
    readJoblog();
    return false;
  }
  void cancel() override {
    if (pid_ <= 0) return;
    // parallel passes TERM on to its jobs (its --termseq) and ends; its jobs run in groups of
    // their own, so the group of parallel alone is not enough.
    ::kill(pid_, SIGTERM);
    ::kill(pid_, SIGTERM);
    stopGroup(pid_, 10);
    pid_ = -1;
    readJoblog();
  }
  std::map<std::size_t, int> exitStatuses() const override { return statuses_; }

 private:
  void readJoblog() {
    std::ifstream in(joblog_);
    std::string line;
    std::getline(in, line);  // Seq Host Starttime JobRuntime Send Receive Exitval Signal Command
    while (std::getline(in, line)) {
      std::stringstream ss(line);
      std::string field;
      std::vector<std::string> fields;
      while (fields.size() < 8 && std::getline(ss, field, '\t')) fields.push_back(field);
      if (fields.size() < 8) continue;
      const std::size_t seq = std::strtoul(fields[0].c_str(), nullptr, 10);
      if (seq < 1 || seq > chunks_.size()) continue;
      const int code = std::atoi(fields[6].c_str()), signal = std::atoi(fields[7].c_str());
      statuses_[chunks_[seq - 1]] = signal ? 128 + signal : code;
    }
  }
  int jobs_;
  std::string sshlogin_, dir_, joblog_;
  pid_t pid_ = -1;
  std::vector<std::size_t> chunks_;
  std::map<std::size_t, int> statuses_;
};

// Slurm: job arrays of at most MaxArraySize tasks, each task one line of a task file; the jobs
// carry the batch folder's name so that their end (and leftovers) can be found with squeue.
class SlurmRunner : public BatchRunner {
 public:
  explicit SlurmRunner(std::string dir) : dir_(std::move(dir)) {
    std::string out;
    for (const char* tool : {"sbatch", "squeue", "scancel", "scontrol"})
      if (runCaptured({"sh", "-c", std::string("command -v ") + tool}, out, 10) != 0)
        throw RunFailure("--runner slurm", std::string(tool) + " is not installed (apt-get install slurm-client)");
    // Slurm's clients wait a minute for a configuration file that is not there.
    const char* conf = std::getenv("SLURM_CONF");
    const std::string confFile = conf && *conf ? conf : "/etc/slurm/slurm.conf";
    if (!fs::exists(confFile))
      throw RunFailure("--runner slurm", "no Slurm configuration: " + confFile + " does not exist (SLURM_CONF chooses " +
                                             "it; tools/slurm-local.sh start makes one on this machine)");
    if (runCaptured({"scontrol", "ping"}, out, 30) != 0 || out.find(" is UP") == std::string::npos)
      throw RunFailure("--runner slurm", "no Slurm controller answers (scontrol ping: " + firstLine(out) +
                                             "); tools/slurm-local.sh start makes one on this machine");
    if (runCaptured({"scontrol", "show", "config"}, out, 30) == 0) {
      const auto at = out.find("MaxArraySize");
      if (at != std::string::npos) maxArray_ = std::max(2L, std::strtol(out.c_str() + out.find('=', at) + 1, nullptr, 10));
    }
    name_ = "nao-batch-" + std::to_string(std::hash<std::string>{}(fs::absolute(dir_).string()) % 1000000);
    std::vector<std::string> ids;
    if (queued(ids) && !ids.empty())
      throw RunFailure("--runner slurm", "Slurm still has jobs of this batch (" + name_ +
                                             "): scancel --name " + name_ + ", or wait for them, then --resume");
  }
  void start(const std::vector<BatchTask>& tasks) override {
    const std::string stamp = std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
    const std::string taskFile = dir_ + "/slurm-tasks-" + stamp + ".txt";
    std::ofstream f(taskFile, std::ios::trunc);
    for (const auto& t : tasks) f << commandLine(t.argv) << " >> " << shellQuote(t.log) << " 2>&1\n";
    f.close();
    const std::string script = dir_ + "/slurm-task.sh";
    std::ofstream s(script, std::ios::trunc);
    s << "#!/bin/sh\n"
         "# One task of a nao-soccer batch: line SLURM_ARRAY_TASK_ID + NAO_BATCH_OFFSET + 1 of the task file $1.\n"
         "n=$((SLURM_ARRAY_TASK_ID + ${NAO_BATCH_OFFSET:-0} + 1))\n"
         "line=$(sed -n \"${n}p\" \"$1\")\n"
         "[ -n \"$line\" ] || { echo \"no task $n in $1\" >&2; exit 2; }\n"
         "exec /bin/sh -c \"$line\"\n";
    s.close();
    if (!f || !s) throw RunFailure(dir_, "the task files cannot be written");
    fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
    fs::create_directories(dir_ + "/slurm");
    const long n = static_cast<long>(tasks.size());
    for (long offset = 0; offset < n; offset += maxArray_ - 1) {
      const long count = std::min(n - offset, maxArray_ - 1);
      std::string out;
      const int rc = runCaptured({"sbatch", "--parsable", "--job-name=" + name_, "--array=0-" + std::to_string(count - 1),
                                  "--output=" + dir_ + "/slurm/%A_%a.out", "--chdir=" + fs::current_path().string(),
                                  "--export=ALL,NAO_BATCH_OFFSET=" + std::to_string(offset), "--cpus-per-task=1", script,
                                  taskFile},
                                 out, 120);
      if (rc != 0) {
        cancel();
        throw RunFailure("--runner slurm", "sbatch refused the job array: " + firstLine(out));
      }
      jobs_.push_back(firstLine(out).substr(0, out.find(';')));
    }
  }
  bool busy() override {
    std::vector<std::string> ids;
    const auto now = std::chrono::steady_clock::now();
    if (queued(ids)) {
      failing_ = false;
      return !ids.empty();
    }
    // A controller that stops answering for a minute ends the wait: the rows tell what ran.
    if (!failing_) failingSince_ = now;
    failing_ = true;
    if (now - failingSince_ < std::chrono::seconds(60)) return true;
    std::fprintf(stderr, "batch: squeue has failed for a minute; the tasks' rows say what ran\n");
    return false;
  }
  void cancel() override {
    std::string out;
    runCaptured({"scancel", "--name", name_}, out, 60);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::vector<std::string> ids;
    while (queued(ids) && !ids.empty() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  std::map<std::size_t, int> exitStatuses() const override { return {}; }

 private:
  // The ids of this batch's jobs Slurm still has, pending or running; false when squeue fails.
  bool queued(std::vector<std::string>& ids) {
    ids.clear();
    std::string out;
    if (runCaptured({"squeue", "-h", "--name", name_, "-o", "%i"}, out, 60) != 0) return false;
    std::stringstream ss(out);
    std::string line;
    while (std::getline(ss, line))
      if (!line.empty()) ids.push_back(line);
    return true;
  }
  std::string dir_, name_;
  long maxArray_ = 1001;
  std::vector<std::string> jobs_;
  bool failing_ = false;
  std::chrono::steady_clock::time_point failingSince_;
};

}  // namespace

std::unique_ptr<BatchRunner> makeBatchRunner(const std::string& runner, int jobs, const std::string& sshlogin,
                                             const std::string& dir) {
  if (runner == "local") return std::make_unique<LocalRunner>(jobs);
  if (runner == "parallel") return std::make_unique<ParallelRunner>(jobs, sshlogin, dir);
  if (runner == "slurm") return std::make_unique<SlurmRunner>(dir);
  throw Error("--runner", runner + " is not one of local, parallel, slurm");
}

}  // namespace nao::cli
