#pragma once
// The state of one behaviour option: which state it is in and since when (a CABSL-style
// option is a class with an enum of states and a switch over them).
namespace nao::behavior {

template <class State>
struct StateMachine {
  State state;
  double since = 0;  // s, when `state` was entered

  explicit StateMachine(State initial) : state(initial) {}
  // Enters s at time t (staying in the same state keeps its start time).
  void go(State s, double t) {
    if (s == state) return;
    state = s;
    since = t;
  }
  double timeIn(double t) const { return t - since; }
};

}  // namespace nao::behavior
