#pragma once
// The robot's voice on a NAO: each utterance goes to a text-to-speech command (default
// `flite -t`, what the teams ship: NAOqi's speech starts minutes after boot), the text as its
// last argument, one utterance after the other in a thread of its own, so that neither the
// motion cycle nor cognition waits for it. Every utterance is logged ("speech: <text>"), and a
// command that cannot run or fails is logged once per utterance, never fatal: the robot must
// play on without a voice.
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace nao {

class SpeechOutput {
 public:
  using Log = std::function<void(const std::string&)>;
  // command: the program and its first arguments, split at spaces ("" = log only).
  SpeechOutput(const std::string& command, Log log);
  ~SpeechOutput();  // ends the utterance being spoken (SIGTERM) and drops the rest
  SpeechOutput(const SpeechOutput&) = delete;
  SpeechOutput& operator=(const SpeechOutput&) = delete;

  // Queues the text (cheap: callable from the motion cycle).
  void say(const std::string& text);
  // Utterances spoken (the command ended with status 0) and failed, so far.
  int spoken() const;
  int failed() const;

  static std::vector<std::string> split(const std::string& command);

 private:
  void loop();
  void speak(const std::string& text);

  std::vector<std::string> command_;
  Log log_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::string> queue_;
  bool stop_ = false;
  int spoken_ = 0, failed_ = 0;
  int child_ = 0;  // the command speaking now (its pid), 0: none
  std::thread thread_;
};

}  // namespace nao
