// The modules the NAO app's board writes became: ButtonStateProvider (gestures from the Touch
// array), GameStateProvider (the GameController, or the chest button without one) and
// LedControl (the chest colour the rules ask for). Each alone through the harness; the
// expectations are the rules' (../shared/reference/protocols.md), typed out here.
#include <gtest/gtest.h>

#include "representations/infrastructure/ButtonState.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/infrastructure/GameState.h"
#include "representations/infrastructure/SafetyState.h"
#include "robot/JointIds.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"
#include "robot/nao/GameController.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

SensorFrame touching(double t, std::initializer_list<int> pressed) {
  SensorFrame f;
  f.time = t;
  for (int i : pressed) f.touch[i] = 1.0;
  return f;
}

// Events over a sequence of (time, pressed buttons) frames, 12 ms apart.
std::vector<ButtonEvent> eventsOf(ModuleHarness& h, double from, double to, std::initializer_list<int> pressed) {
  std::vector<ButtonEvent> events;
  for (double t = from; t < to - 1e-9; t += 0.012) {
    h.fix(touching(t, pressed)).run();
    for (ButtonEvent e : h.get<ButtonState>().events) events.push_back(e);
  }
  return events;
}

TEST(ButtonStateProvider, ChestPressOnReleaseAndHeldCombinations) {
  ModuleHarness h("ButtonStateProvider");
  EXPECT_TRUE(eventsOf(h, 0, 0.5, {}).empty());
  // Chest alone: the press counts when released, once.
  EXPECT_TRUE(eventsOf(h, 0.5, 0.7, {ChestButton}).empty());
  EXPECT_TRUE(h.get<ButtonState>().chest);
  EXPECT_EQ(eventsOf(h, 0.7, 0.8, {}), std::vector<ButtonEvent>{ButtonEvent::ChestPress});
  EXPECT_FALSE(h.get<ButtonState>().chest);
  // All three head buttons: unstiffen after 1 s held, not before, and once.
  EXPECT_TRUE(eventsOf(h, 1.0, 1.9, {HeadFront, HeadMiddle, HeadRear}).empty());
  EXPECT_EQ(eventsOf(h, 1.9, 3.0, {HeadFront, HeadMiddle, HeadRear}), std::vector<ButtonEvent>{ButtonEvent::Unstiffen});
  // Chest + head front held 1 s: the calibration; the chest's release is then no press.
  auto events = eventsOf(h, 3.0, 4.2, {ChestButton, HeadFront});
  EXPECT_EQ(events, std::vector<ButtonEvent>{ButtonEvent::StartCalibration});
  EXPECT_TRUE(eventsOf(h, 4.2, 4.4, {}).empty());
}

TEST(ButtonStateProvider, NoTouchNoEvents) {  // the simulator's runs
  ModuleHarness h("ButtonStateProvider");
  EXPECT_TRUE(eventsOf(h, 0, 5, {}).empty());
}

ButtonState chestPress() {
  ButtonState b;
  b.events = {ButtonEvent::ChestPress};
  return b;
}

TEST(GameStateProvider, WithoutGameControllerOrButtonsItStaysInitial) {
  ModuleHarness h("GameStateProvider");
  h.fix(GameControllerData{}).fix(ButtonState{}).fix(SafetyState{});
  for (int i = 0; i < 100; ++i) h.run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Initial);
  EXPECT_FALSE(h.get<GameState>().penalised());
  EXPECT_FALSE(h.get<GameState>().fromGameController);
}

TEST(GameStateProvider, ChestButtonPlaysPenalisedThenTogglesThePenalty) {
  ModuleHarness h("GameStateProvider");
  GameControllerData data;
  data.state.teamNumber = 12;
  data.state.playerNumber = 3;
  h.fix(data).fix(ButtonState{}).fix(SafetyState{}).run();
  EXPECT_EQ(h.get<GameState>().teamNumber, 12);
  EXPECT_EQ(h.get<GameState>().playerNumber, 3);
  h.fix(chestPress()).run();  // INITIAL -> PLAYING, penalised (the rules' manual start)
  EXPECT_EQ(h.get<GameState>().state, gc::State::Playing);
  EXPECT_EQ(h.get<GameState>().penalty, gc::Penalty::Manual);
  h.fix(ButtonState{}).run();  // nothing pressed: nothing changes
  EXPECT_TRUE(h.get<GameState>().penalised());
  h.fix(chestPress()).run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Playing);
  EXPECT_FALSE(h.get<GameState>().penalised());
  h.fix(chestPress()).run();
  EXPECT_EQ(h.get<GameState>().penalty, gc::Penalty::Manual);
}

TEST(GameStateProvider, AChestPressThatStiffensAgainIsNoGamePress) {
  ModuleHarness h("GameStateProvider");
  h.fix(GameControllerData{}).fix(chestPress()).fix(SafetyState{true}).run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Initial);
  EXPECT_FALSE(h.get<GameState>().penalised());
}

TEST(GameStateProvider, TheGameControllerDecidesWhileActiveAndIsKeptAfterwards) {
  ModuleHarness h("GameStateProvider");
  GameControllerData data;
  data.active = true;
  data.state.state = gc::State::Set;
  data.state.fromGameController = true;
  data.state.secsRemaining = 421;
  h.fix(data).fix(chestPress()).fix(SafetyState{}).run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Set);  // the chest press is ignored
  EXPECT_FALSE(h.get<GameState>().penalised());
  EXPECT_EQ(h.get<GameState>().secsRemaining, 421);
  // The GameController goes quiet: its last state stays, and the chest button takes over from it.
  data.active = false;
  data.state = GameState{};
  h.fix(data).fix(ButtonState{}).run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Set);
  h.fix(chestPress()).run();
  EXPECT_EQ(h.get<GameState>().state, gc::State::Set);
  EXPECT_EQ(h.get<GameState>().penalty, gc::Penalty::Manual);
  EXPECT_FALSE(h.get<GameState>().fromGameController);
}

TEST(LedControl, ChestShowsTheGameState) {
  ModuleHarness h("LedControl");
  struct Case {
    gc::State state;
    bool penalised;
    std::array<double, 3> rgb;
  };
  // The rules: off in INITIAL and FINISHED, blue READY, yellow SET, green PLAYING, red penalised.
  for (const Case& c : {Case{gc::State::Initial, false, {0, 0, 0}}, Case{gc::State::Ready, false, {0, 0, 1}},
                        Case{gc::State::Set, false, {1, 1, 0}}, Case{gc::State::Playing, false, {0, 1, 0}},
                        Case{gc::State::Playing, true, {1, 0, 0}}, Case{gc::State::Finished, false, {0, 0, 0}}}) {
    GameState g;
    g.state = c.state;
    if (c.penalised) g.penalty = gc::Penalty::PlayerPushing;
    h.fix(g).run();
    EXPECT_EQ(h.get<LedRequest>().chest, c.rgb) << gc::stateName(c.state) << (c.penalised ? " penalised" : "");
    for (double v : h.get<LedRequest>().leftEye) EXPECT_EQ(v, 0);
  }
}

}  // namespace
}  // namespace nao
