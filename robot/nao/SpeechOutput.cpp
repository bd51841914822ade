#include "robot/nao/SpeechOutput.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <sstream>

extern char** environ;

namespace nao {

std::vector<std::string> SpeechOutput::split(const std::string& command) {
  std::vector<std::string> words;
  std::istringstream in(command);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

SpeechOutput::SpeechOutput(const std::string& command, Log log) : command_(split(command)), log_(std::move(log)) {
  thread_ = std::thread([this] { loop(); });
}

SpeechOutput::~SpeechOutput() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
    if (child_ > 0) kill(child_, SIGTERM);  // a hung command must not hold the program's stop
  }
  wake_.notify_all();
  thread_.join();
}

void SpeechOutput::say(const std::string& text) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(text);
  }
  wake_.notify_all();
}

int SpeechOutput::spoken() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return spoken_;
}

int SpeechOutput::failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failed_;
}

void SpeechOutput::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    const std::string text = queue_.front();
    queue_.pop_front();
    lock.unlock();
    speak(text);
    lock.lock();
  }
}

void SpeechOutput::speak(const std::string& text) {
  log_("speech: " + text);
  if (command_.empty()) return;
  std::vector<std::string> words = command_;
  words.push_back(text);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  // The command's output is the robot's log's; its input is nothing.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  int err = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) return;
    err = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    if (err == 0) child_ = pid;
  }
  posix_spawn_file_actions_destroy(&actions);
  std::string problem;
  if (err != 0) {
    problem = std::string("cannot start: ") + std::strerror(err);
  } else {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    std::lock_guard<std::mutex> lock(mutex_);
    child_ = 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0) problem = "exit status " + std::to_string(WEXITSTATUS(status));
    else if (WIFSIGNALED(status)) problem = std::string("killed by signal ") + std::to_string(WTERMSIG(status));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (problem.empty()) {
    ++spoken_;
  } else {
    ++failed_;
    log_("speech: the command '" + command_[0] + "' failed (" + problem + "; --speech-command)");
  }
}

}  // namespace nao
