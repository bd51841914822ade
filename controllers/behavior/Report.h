#pragma once
// Option: report the way the Autonomous Calibration Challenge's referee listens: stand, raise
// one arm, say the text once the arm is up, keep it up for holdTime (the referee looks and
// notes), lower it. Speaking does not wait longer than armTimeout for the arm: a report with the
// arm still rising is better than none.
#include <string>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/StateMachine.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "representations/behavior/SpeechRequest.h"

namespace nao::behavior {

// Says `text` once: a new id on the request.
inline void say(SpeechRequest& speech, const std::string& text) {
  speech.text = text;
  ++speech.id;
}

class Report {
 public:
  struct Params {
    double holdTime = 2.0;    // s, arm up after speaking
    double armTimeout = 3.0;  // s: speak even when the arm is not up by then
    bool leftArm = false;     // else the right one
  };
  enum class State { Idle, Raising, Holding, Done };

  Report() = default;
  explicit Report(const Params& params) : params_(params) {}
  // A new report (any running one is dropped).
  void start(const std::string& text, double time);
  // Fills the arm and speech requests (the caller asks the motion to stand); true once done.
  bool run(const BehaviorInput& in, ArmMotionRequest& arm, SpeechRequest& speech);
  State state() const { return machine_.state; }
  bool active() const { return machine_.state == State::Raising || machine_.state == State::Holding; }

 private:
  Params params_;
  StateMachine<State> machine_{State::Idle};
  std::string text_;
};

template <class V>
void describe(V& v, Report::Params& p) {
  v("holdTime", p.holdTime, 0.0, 30.0);
  v("armTimeout", p.armTimeout, 0.0, 30.0);
  v("leftArm", p.leftArm);
}

}  // namespace nao::behavior
