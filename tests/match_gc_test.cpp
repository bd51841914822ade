// The simulated 1vs1 game's GameController (scenarios/GameControllerSim.h) against the 2021
// rules' timings (../shared/reference/referee-and-match.md), and its packets against the NAO's
// own decoder and an independent one written from the published v18 byte layout
// (../shared/reference/protocols.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "robot/Error.h"
#include "robot/nao/GameController.h"
#include "scenarios/GameControllerSim.h"

namespace {

using nao::sim::GameControllerSim;
using nao::sim::PenaltyRule;
using State = nao::gc::State;

constexpr double kStep = 0.012;  // the referee's cycle

// Runs the GameController from t to t + seconds in robot cycles; returns the new time.
double run(GameControllerSim& g, double t, double seconds) {
  const int n = static_cast<int>(std::lround(seconds / kStep));
  for (int i = 1; i <= n; ++i) g.update(t + i * kStep);
  return t + n * kStep;
}

// Steps until the state comes (at most 60 s); returns the time it came.
double until(GameControllerSim& g, double t, State s) {
  for (int i = 0; i < 5000 && g.state() != s; ++i) g.update(t += kStep);
  return t;
}

double toPlaying(GameControllerSim& g, double t) {
  g.ready(t);
  g.set(t + 10);
  return run(g, t + 10, 5.1);
}

TEST(GameControllerSim, ReadyEndsAfter45sAndTheWhistleFollowsSet) {
  GameControllerSim g;
  EXPECT_EQ(g.state(), State::Initial);
  g.update(20);
  EXPECT_EQ(g.state(), State::Initial);  // nothing runs before the kick-off
  g.ready(20);
  double t = run(g, 20, 30);
  EXPECT_EQ(g.state(), State::Ready);
  EXPECT_EQ(g.data().secondaryTime, 15);  // READY's time left, as the GameController shows it
  t = run(g, t, 14.9);
  EXPECT_EQ(g.state(), State::Ready);
  t = until(g, t, State::Set);
  EXPECT_NEAR(t, 20 + 45, 0.013);
  t = run(g, t, 4.9);
  EXPECT_EQ(g.state(), State::Set);
  EXPECT_EQ(g.secsRemaining(), 300);  // the clock starts with the kick-off's PLAYING
  t = run(g, t, 0.2);
  EXPECT_EQ(g.state(), State::Playing);
  run(g, t, 60);
  EXPECT_NEAR(g.secsRemaining(), 240, 0.2);
  // An early SET (every robot in position) is the operator's button.
  GameControllerSim h;
  h.ready(0);
  h.set(3);
  EXPECT_EQ(h.state(), State::Set);
  EXPECT_THROW(h.ready(4), nao::Error);
}

TEST(GameControllerSim, TheClockStopsInAGlobalGameStuckAndTheHalvesEnd) {
  GameControllerSim g;
  double t = toPlaying(g, 0);
  t = run(g, t, 100);
  EXPECT_NEAR(g.secsRemaining(), 200, 0.2);
  g.globalGameStuck(t);
  EXPECT_EQ(g.state(), State::Ready);
  t = run(g, t, 30);
  EXPECT_NEAR(g.secsRemaining(), 200, 0.2);  // stopped in READY and SET
  g.set(t);
  t = run(g, t, 5.1);
  EXPECT_EQ(g.state(), State::Playing);
  g.point(0, t);
  EXPECT_EQ(g.state(), State::Playing);  // a point does not stop play
  EXPECT_EQ(g.score(0), 1);
  t = run(g, t, 200.5);
  EXPECT_EQ(g.state(), State::Finished);
  EXPECT_TRUE(g.firstHalf());
  EXPECT_FALSE(g.finished());
  g.startSecondHalf(t + 300);
  EXPECT_EQ(g.state(), State::Initial);
  EXPECT_FALSE(g.firstHalf());
  EXPECT_EQ(g.secsRemaining(), 300);
  t = toPlaying(g, t + 300);
  run(g, t, 300.5);
  EXPECT_TRUE(g.finished());  // 1:0, no extension
  EXPECT_EQ(g.winner(), 0);
  EXPECT_EQ(g.extensions(), 0);
}

TEST(GameControllerSim, ADrawIsExtendedFiveTimesByAMinuteThenTossed) {
  GameControllerSim::Config c;
  c.halfSeconds = 10;
  GameControllerSim g(c);
  double t = toPlaying(g, 0);
  t = run(g, t, 10.5);
  g.startSecondHalf(t);
  t = toPlaying(g, t);
  t = run(g, t, 10.5);
  EXPECT_EQ(g.state(), State::Playing);  // 0:0: the first extension
  EXPECT_EQ(g.extensions(), 1);
  EXPECT_EQ(g.data().gamePhase, nao::gc::GamePhase::Overtime);
  t = run(g, t, 4 * 60.0 + 0.5);
  EXPECT_EQ(g.extensions(), 5);
  EXPECT_FALSE(g.finished());
  t = run(g, t, 60);
  EXPECT_TRUE(g.finished());
  EXPECT_EQ(g.state(), State::Finished);
  EXPECT_EQ(g.winner(), -1);
  g.coinToss(1, t);
  EXPECT_EQ(g.winner(), 1);
  // A point in an extension ends the game at that extension's end.
  GameControllerSim h(c);
  t = toPlaying(h, 0);
  t = run(h, t, 10.5);
  h.startSecondHalf(t);
  t = toPlaying(h, t);
  t = run(h, t, 10.5 + 20);
  h.point(1, t);
  run(h, t, 41);
  EXPECT_TRUE(h.finished());
  EXPECT_EQ(h.extensions(), 1);
  EXPECT_EQ(h.winner(), 1);
}

TEST(GameControllerSim, PenaltiesLastWhatTheRulesSay) {
  GameControllerSim::Config c;
  c.players = 2;
  GameControllerSim g(c);
  double t = toPlaying(g, 0);
  // Standard removals: 45 s, then +10 s for every earlier one of the same team.
  EXPECT_DOUBLE_EQ(g.penalise(0, 1, PenaltyRule::HalfwayLine, t), 45);
  EXPECT_DOUBLE_EQ(g.penalise(0, 1, PenaltyRule::LeavingTheField, t), 0);  // already out
  EXPECT_DOUBLE_EQ(g.penalise(0, 2, PenaltyRule::LeavingTheField, t), 55);
  EXPECT_DOUBLE_EQ(g.penalise(1, 1, PenaltyRule::PlayerStance, t), 45);  // the other team's first
  // Fallen and inactive: 45 s, not incremental; they count towards the hardware limit.
  EXPECT_DOUBLE_EQ(g.penalise(1, 2, PenaltyRule::FallenRobot, t), 45);
  EXPECT_EQ(g.data().teams[0].players[0].penalty, static_cast<std::uint8_t>(nao::gc::Penalty::LeavingTheField));
  EXPECT_EQ(g.data().teams[1].players[1].penalty, static_cast<std::uint8_t>(nao::gc::Penalty::InactivePlayer));
  EXPECT_EQ(g.data().teams[0].players[1].secsTillUnpenalised, 55);
  t = run(g, t, 44.9);
  EXPECT_TRUE(g.penalised(0, 1));
  t = run(g, t, 0.2);
  EXPECT_FALSE(g.penalised(0, 1));
  EXPECT_FALSE(g.penalised(1, 2));
  EXPECT_TRUE(g.penalised(0, 2));
  // Penalty time does not run in SET.
  g.globalGameStuck(t);
  t = run(g, t, 5);  // READY: runs
  EXPECT_NEAR(g.penaltyLeft(0, 2), 4.9, 0.05);
  g.set(t);
  t = run(g, t, 4.9);
  EXPECT_NEAR(g.penaltyLeft(0, 2), 4.9, 0.05);
  EXPECT_TRUE(g.penalised(0, 2));
  // Motion in SET: until PLAYING; illegal position in SET: 15 s.
  EXPECT_DOUBLE_EQ(g.penalise(1, 1, PenaltyRule::MotionInSet, t), -1);
  EXPECT_DOUBLE_EQ(g.penalise(1, 2, PenaltyRule::IllegalPositionInSet, t), 15);
  t = run(g, t, 0.2);
  EXPECT_EQ(g.state(), State::Playing);
  EXPECT_FALSE(g.penalised(1, 1));
  EXPECT_TRUE(g.penalised(1, 2));
  // A penalty ends with the half.
  EXPECT_GT(g.penalise(0, 1, PenaltyRule::GoalArea, t), 45);
  run(g, t, g.secsRemaining() + 0.1);
  EXPECT_EQ(g.state(), State::Finished);
  EXPECT_FALSE(g.penalised(0, 1));
  EXPECT_FALSE(g.penalised(1, 2));
}

TEST(GameControllerSim, TheFourthHardwarePenaltyExcludesTheRobot) {
  GameControllerSim g;
  double t = toPlaying(g, 0);
  const PenaltyRule rules[] = {PenaltyRule::FallenRobot, PenaltyRule::InactiveRobot, PenaltyRule::RequestForPickup};
  for (PenaltyRule r : rules) {
    EXPECT_DOUBLE_EQ(g.penalise(0, 1, r, t), 45);
    t = run(g, t, 45.1);
    EXPECT_FALSE(g.penalised(0, 1));
  }
  EXPECT_EQ(g.hardwarePenalties(0, 1), 3);
  EXPECT_DOUBLE_EQ(g.penalise(0, 1, PenaltyRule::FallenRobot, t), 0);
  EXPECT_TRUE(g.excluded(0, 1));
  t = run(g, t, 100);
  EXPECT_TRUE(g.penalised(0, 1));  // for the rest of the game
  // Standard penalties do not count towards the limit.
  GameControllerSim h;
  t = toPlaying(h, 0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GT(h.penalise(1, 1, PenaltyRule::LeavingTheField, t), 0);
    t = run(h, t, 80);
  }
  EXPECT_FALSE(h.excluded(1, 1));
  EXPECT_EQ(h.hardwarePenalties(1, 1), 0);
}

TEST(GameControllerSim, RuleNamesAreTheContractsAndAnUnknownOneIsNamed) {
  for (const char* name : {"leaving_the_field", "halfway_line", "goal_area", "fallen_robot", "inactive_robot",
                           "player_stance", "playing_with_arms", "illegal_position_in_set", "motion_in_set",
                           "request_for_pickup"})
    EXPECT_STREQ(nao::sim::ruleName(nao::sim::ruleNamed(name)), name);
  try {
    nao::sim::ruleNamed("pushing_hard");
    FAIL() << "an unknown rule was accepted";
  } catch (const nao::Error& e) {
    EXPECT_NE(std::string(e.what()).find("pushing_hard"), std::string::npos) << e.what();
  }
}

// Read from the published layout alone: little-endian, packed, 118 bytes.
struct Decoded {
  std::string header;
  int version, packetNumber, players, gamePhase, state, firstHalf, kickingTeam, secsRemaining, secondaryTime;
  int team[2], colour[2], score[2], penalty[2][2], secs[2][2];
};

Decoded decode(const std::uint8_t* b) {
  auto i16 = [&](int o) { return static_cast<int>(static_cast<std::int16_t>(b[o] | (b[o + 1] << 8))); };
  Decoded d{};
  d.header.assign(reinterpret_cast<const char*>(b), 4);
  d.version = b[4];
  d.packetNumber = b[5];
  d.players = b[6];
  d.gamePhase = b[9];
  d.state = b[10];
  d.firstHalf = b[12];
  d.kickingTeam = b[13];
  d.secsRemaining = i16(14);
  d.secondaryTime = i16(16);
  for (int k = 0; k < 2; ++k) {
    const int o = 18 + 50 * k;
    d.team[k] = b[o];
    d.colour[k] = b[o + 1];
    d.score[k] = b[o + 4];
    for (int p = 0; p < 2; ++p) {
      d.penalty[k][p] = b[o + 10 + 2 * p];
      d.secs[k][p] = b[o + 11 + 2 * p];
    }
  }
  return d;
}

TEST(GameControllerSim, PacketsDecodeWithTheNaosDecoderAndFromThePublishedLayout) {
  GameControllerSim::Config c;
  c.teams = {12, 34};
  c.colours = {2, 7};
  GameControllerSim g(c);
  double t = toPlaying(g, 0);
  t = run(g, t, 20);
  g.point(1, t);
  g.penalise(0, 1, PenaltyRule::InactiveRobot, t);
  t = run(g, t, 10);
  const auto first = g.packet();
  const auto bytes = g.packet();
  const Decoded d = decode(bytes.data());
  EXPECT_EQ(d.header, "RGme");
  EXPECT_EQ(d.version, 18);
  EXPECT_EQ(d.packetNumber, decode(first.data()).packetNumber + 1);
  EXPECT_EQ(d.players, 1);
  EXPECT_EQ(d.state, 3);
  EXPECT_EQ(d.firstHalf, 1);
  EXPECT_EQ(d.kickingTeam, 255);
  EXPECT_NEAR(d.secsRemaining, 300 - 30, 1);
  EXPECT_EQ(d.team[0], 12);
  EXPECT_EQ(d.team[1], 34);
  EXPECT_EQ(d.colour[1], 7);
  EXPECT_EQ(d.score[0], 0);
  EXPECT_EQ(d.score[1], 1);
  EXPECT_EQ(d.penalty[0][0], 4);  // inactive player
  EXPECT_NEAR(d.secs[0][0], 35, 1);
  EXPECT_EQ(d.penalty[1][0], 0);
  // The NAO's own decoder, and the robot's GameController fed the packet.
  const nao::gc::GameControlData n = nao::gc::parseGameControlData(bytes.data(), bytes.size());
  EXPECT_EQ(n.state, State::Playing);
  EXPECT_EQ(n.teams[1].score, 1);
  EXPECT_EQ(n.teams[0].players[0].secsTillUnpenalised, d.secs[0][0]);
  for (int team : {12, 34}) {
    nao::GameController::Config rc;
    rc.team = team;
    rc.port = 0;
    nao::GameController robot(rc);
    ASSERT_TRUE(robot.handlePacket(bytes.data(), bytes.size(), t));
    EXPECT_EQ(robot.state().state, State::Playing);
    EXPECT_EQ(robot.state().penalised(), team == 12);
    EXPECT_EQ(robot.state().ownScore, team == 12 ? 0 : 1);
    EXPECT_EQ(robot.state().opponentScore, team == 12 ? 1 : 0);
  }
}

TEST(GameControllerSim, PacketsGoOutAtTwoHertzOfSimulatedTime) {
  GameControllerSim g;
  int sent = 0;
  for (int i = 0; i < static_cast<int>(10 / kStep); ++i) sent += g.packetDue(i * kStep);
  EXPECT_GE(sent, 19);
  EXPECT_LE(sent, 21);
}

}  // namespace
