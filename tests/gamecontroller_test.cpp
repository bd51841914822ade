// The GameController protocol (v18) and the buttons. Packets are built here byte by byte from
// the documented layout (../shared/reference/protocols.md), sent over real UDP on the loopback
// interface to the robot's receiver, and drive its game state; its return packets are read
// back byte by byte.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

#include "robot/Error.h"
#include "robot/nao/GameController.h"

namespace nao {
namespace {

// ---- packets from the documented layout -----------------------------------------------------
struct Bytes {
  std::vector<std::uint8_t> b;
  Bytes& u8(int v) {
    b.push_back(static_cast<std::uint8_t>(v));
    return *this;
  }
  Bytes& u16(int v) { return u8(v & 0xff).u8((v >> 8) & 0xff); }  // little-endian
  Bytes& text(const char* s) {
    for (; *s; ++s) u8(*s);
    return *this;
  }
};

struct Team {
  int number = 0, fieldColour = 0, goalkeeperColour = 1, goalkeeper = 1, score = 0;
  std::array<int, 20> penalty{}, secs{};
};

// RoboCupGameControlData v18: 118 bytes.
std::vector<std::uint8_t> gcPacket(int state, const Team& a, const Team& b, int version = 18, int packetNumber = 7,
                                   int setPlay = 0, int kickingTeam = 255, int secsRemaining = 480) {
  Bytes p;
  p.text("RGme").u8(version).u8(packetNumber);
  p.u8(5)       // playersPerTeam
      .u8(0)    // competitionPhase
      .u8(0)    // competitionType
      .u8(0)    // gamePhase
      .u8(state)
      .u8(setPlay)
      .u8(1)  // firstHalf
      .u8(kickingTeam)
      .u16(secsRemaining)
      .u16(15);  // secondaryTime
  for (const Team* t : {&a, &b}) {
    p.u8(t->number).u8(t->fieldColour).u8(t->goalkeeperColour).u8(t->goalkeeper).u8(t->score);
    p.u8(0)       // penaltyShot
        .u16(0)   // singleShots
        .u16(1200);  // messageBudget
    for (int i = 0; i < 20; ++i) p.u8(t->penalty[i]).u8(t->secs[i]);
  }
  return p.b;
}

Team team(int number) {
  Team t;
  t.number = number;
  return t;
}

TEST(GameControlData, LayoutIs118BytesAndParses) {
  Team own = team(12), other = team(34);
  own.penalty[2] = 2;  // player 3: pushing
  own.secs[2] = 45;
  own.score = 3;
  other.fieldColour = 1;
  const auto bytes = gcPacket(3, own, other, 18, 200, 4, 12, -5);
  ASSERT_EQ(bytes.size(), 118u);
  const gc::GameControlData d = gc::parseGameControlData(bytes.data(), bytes.size());
  EXPECT_EQ(d.packetNumber, 200);
  EXPECT_EQ(d.playersPerTeam, 5);
  EXPECT_EQ(d.state, gc::State::Playing);
  EXPECT_EQ(d.setPlay, gc::SetPlay::KickIn);
  EXPECT_EQ(d.kickingTeam, 12);
  EXPECT_EQ(d.secsRemaining, -5);
  EXPECT_EQ(d.secondaryTime, 15);
  EXPECT_EQ(d.teams[0].teamNumber, 12);
  EXPECT_EQ(d.teams[0].score, 3);
  EXPECT_EQ(d.teams[0].messageBudget, 1200);
  EXPECT_EQ(d.teams[0].players[2].penalty, 2);
  EXPECT_EQ(d.teams[0].players[2].secsTillUnpenalised, 45);
  EXPECT_EQ(d.teams[1].teamNumber, 34);
  EXPECT_EQ(d.teams[1].fieldPlayerColour, 1);
  // The builder (the simulator's GameController) writes the same bytes.
  const auto again = gc::serialize(d);
  EXPECT_TRUE(std::equal(again.begin(), again.end(), bytes.begin()));
}

std::string rejection(const std::vector<std::uint8_t>& bytes) {
  try {
    gc::parseGameControlData(bytes.data(), bytes.size());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GameControlData, RejectsWrongHeaderVersionLengthAndRanges) {
  const Team a = team(12), b = team(34);
  auto p = gcPacket(0, a, b);
  p[3] = 'x';
  EXPECT_EQ(rejection(p), "GameController packet: header 'RGmx' is not 'RGme' (118 bytes)");
  // v17 packets (an older GameController): the version that arrived is named.
  auto v17 = gcPacket(0, a, b, 17);
  v17.resize(116);
  EXPECT_EQ(rejection(v17).rfind("GameController packet: version 17 arrived, this program speaks version 18", 0), 0u)
      << rejection(v17);
  EXPECT_NE(rejection(gcPacket(0, a, b, 19)).find("version 19 arrived"), std::string::npos);
  auto shortPacket = gcPacket(0, a, b);
  shortPacket.pop_back();
  EXPECT_EQ(rejection(shortPacket), "GameController packet: length 117 bytes, version 18 has 118");
  auto longPacket = gcPacket(0, a, b);
  longPacket.push_back(0);
  EXPECT_NE(rejection(longPacket).find("length 119 bytes"), std::string::npos);
  EXPECT_NE(rejection({'R', 'G'}).find("header"), std::string::npos);
  EXPECT_NE(rejection({}).find("header"), std::string::npos);
  EXPECT_EQ(rejection(gcPacket(6, a, b)), "GameController packet: state: 6 is outside 0..5");
  EXPECT_EQ(rejection(gcPacket(0, a, b, 18, 7, 6)), "GameController packet: setPlay: 6 is outside 0..5");
  Team bad = team(12);
  bad.penalty[4] = 12;
  EXPECT_EQ(rejection(gcPacket(0, bad, b)), "GameController packet: teams[0].players[4].penalty: 12 is not a penalty code");
  bad = team(12);
  bad.goalkeeperColour = 10;
  EXPECT_NE(rejection(gcPacket(0, a, bad)).find("teams[1].goalkeeperColour: 10"), std::string::npos);
}

TEST(ReturnData, DocumentedLayout32Bytes) {
  gc::ReturnData r;
  r.playerNum = 3;
  r.teamNum = 12;
  r.fallen = 1;
  r.pose = {1500.f, -250.5f, 0.75f};
  r.ballAge = 2.5f;
  r.ball = {800.f, -100.f};
  const auto b = gc::serialize(r);
  ASSERT_EQ(b.size(), 32u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "RGrt");
  EXPECT_EQ(b[4], 4);   // version
  EXPECT_EQ(b[5], 3);   // playerNum
  EXPECT_EQ(b[6], 12);  // teamNum
  EXPECT_EQ(b[7], 1);   // fallen
  auto f32 = [&](int offset) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | b[static_cast<std::size_t>(offset + i)];  // little-endian
    float f;
    std::memcpy(&f, &v, 4);
    return f;
  };
  EXPECT_EQ(f32(8), 1500.f);
  EXPECT_EQ(f32(12), -250.5f);
  EXPECT_EQ(f32(16), 0.75f);
  EXPECT_EQ(f32(20), 2.5f);
  EXPECT_EQ(f32(24), 800.f);
  EXPECT_EQ(f32(28), -100.f);
  const gc::ReturnData back = gc::parseReturnData(b.data(), b.size());
  EXPECT_EQ(back.pose[1], -250.5f);
  EXPECT_THROW(gc::parseReturnData(b.data(), 31), Error);
}

// ---- the receiver over UDP on loopback --------------------------------------------------------
struct Udp {
  int fd = -1;
  std::uint16_t port = 0;
  Udp() {
    fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
  }
  ~Udp() { ::close(fd); }
  void sendTo(std::uint16_t to, const std::vector<std::uint8_t>& bytes) const {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(to);
    ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  std::vector<std::uint8_t> receive(int timeoutMs) const {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeoutMs) <= 0) return {};
    std::vector<std::uint8_t> b(1024);
    const ssize_t n = ::recv(fd, b.data(), b.size(), 0);
    b.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    return b;
  }
};

struct Receiver : ::testing::Test {
  Udp sender;   // the GameController: its packets come from here, its return packets go here
  std::vector<std::string> log;
  std::unique_ptr<GameController> gc;
  double now = 10;
  void SetUp() override {
    GameController::Config c;
    c.team = 12;
    c.player = 3;
    c.port = 0;  // any free port
    c.bindAddress = "127.0.0.1";
    c.returnPort = sender.port;
    gc = std::make_unique<GameController>(c, [this](const std::string& l) { log.push_back(l); });
  }
  // Sends a datagram and lets the receiver take it (as once per cycle).
  int deliver(const std::vector<std::uint8_t>& bytes) {
    sender.sendTo(gc->port(), bytes);
    int accepted = 0;
    for (int i = 0; i < 100 && accepted == 0; ++i) {
      now += 0.012;
      accepted = gc->receive(now);
      if (accepted == 0 && gc->rejected() > rejectedBefore) break;
      usleep(1000);
    }
    rejectedBefore = gc->rejected();
    return accepted;
  }
  bool logged(const std::string& text) const {
    for (const auto& l : log)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }
  int rejectedBefore = 0;
};

TEST_F(Receiver, PacketsDriveTheGameStateFromInitialToFinished) {
  Team own = team(12), other = team(34);
  EXPECT_EQ(gc->state().state, gc::State::Initial);
  EXPECT_FALSE(gc->state().fromGameController);
  const std::vector<std::pair<int, gc::State>> states = {{0, gc::State::Initial}, {5, gc::State::Standby},
                                                         {1, gc::State::Ready},   {2, gc::State::Set},
                                                         {3, gc::State::Playing}, {4, gc::State::Finished}};
  for (const auto& [code, state] : states) {
    ASSERT_EQ(deliver(gcPacket(code, other, own, 18, code, 0, 12)), 1) << code;  // our team second: either side works
    EXPECT_EQ(gc->state().state, state);
    EXPECT_TRUE(gc->state().fromGameController);
    EXPECT_TRUE(gc->state().ownKickOff);
    if (state == gc::State::Playing) {
      // Penalised (player 3 = index 2), then unpenalised.
      own.penalty[2] = 5;
      own.secs[2] = 30;
      ASSERT_EQ(deliver(gcPacket(code, other, own)), 1);
      EXPECT_EQ(gc->state().penalty, gc::Penalty::IllegalPosition);
      EXPECT_EQ(gc->state().secsTillUnpenalised, 30);
      EXPECT_TRUE(gc->state().penalised());
      EXPECT_EQ(chestColour(gc->state()), (std::array<double, 3>{1, 0, 0}));
      own.penalty[3] = 4;  // another player's penalty is not ours
      own.penalty[2] = 0;
      own.secs[2] = 0;
      ASSERT_EQ(deliver(gcPacket(code, other, own)), 1);
      EXPECT_FALSE(gc->state().penalised());
      EXPECT_EQ(chestColour(gc->state()), (std::array<double, 3>{0, 1, 0}));
    }
  }
  EXPECT_TRUE(logged("game: READY"));
  EXPECT_TRUE(logged("game: penalised (illegal position)"));
  EXPECT_TRUE(logged("game: unpenalised"));
  EXPECT_TRUE(logged("game: FINISHED"));
}

TEST_F(Receiver, RejectsOldVersionsMalformedAndOtherTeamsWithALogLine) {
  const Team own = team(12), other = team(34);
  ASSERT_EQ(deliver(gcPacket(1, own, other)), 1);
  auto v17 = gcPacket(3, own, other, 17);
  v17.resize(116);
  EXPECT_EQ(deliver(v17), 0);
  EXPECT_EQ(gc->state().state, gc::State::Ready);
  EXPECT_TRUE(logged("gamecontroller: rejected GameController packet: version 17 arrived, this program speaks version 18"));
  auto truncated = gcPacket(3, own, other);
  truncated.resize(50);
  EXPECT_EQ(deliver(truncated), 0);
  EXPECT_TRUE(logged("length 50 bytes"));
  EXPECT_EQ(deliver({'h', 'e', 'l', 'l', 'o'}), 0);
  EXPECT_TRUE(logged("header 'hell' is not 'RGme'"));
  EXPECT_EQ(deliver(gcPacket(3, team(5), team(6))), 0);
  EXPECT_TRUE(logged("for teams 5 and 6, we are team 12"));
  EXPECT_EQ(gc->state().state, gc::State::Ready);
  EXPECT_EQ(gc->rejected(), 4);
  // A GameController on the wrong version sends 2 Hz: the same reason again within 10 s is
  // counted, not logged again.
  EXPECT_EQ(deliver(v17), 0);
  const std::size_t lines = log.size();
  EXPECT_EQ(deliver(v17), 0);
  EXPECT_EQ(deliver(v17), 0);
  EXPECT_EQ(log.size(), lines);
  EXPECT_EQ(gc->rejected(), 7);
}

TEST_F(Receiver, ReturnPacketsGoToTheGameController) {
  gc::ReturnData r;
  r.playerNum = 3;
  r.teamNum = 12;
  EXPECT_FALSE(gc->sendReturnIfDue(now, r));  // no GameController heard yet
  ASSERT_EQ(deliver(gcPacket(3, team(12), team(34))), 1);
  EXPECT_TRUE(gc->sendReturnIfDue(now, r));
  EXPECT_FALSE(gc->sendReturnIfDue(now + 0.5, r));  // 1 Hz
  const auto b = sender.receive(1000);
  ASSERT_EQ(b.size(), 32u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "RGrt");
  EXPECT_EQ(b[4], 4);
  EXPECT_EQ(b[5], 3);
  EXPECT_EQ(b[6], 12);
  EXPECT_TRUE(gc->sendReturnIfDue(now + 1.0, r));
  EXPECT_EQ(sender.receive(1000).size(), 32u);
  EXPECT_FALSE(gc->sendReturnIfDue(now + 10, r));  // the GameController is gone (5 s)
}

TEST_F(Receiver, ChestButtonWithoutGameController) {
  gc->chestButton(now);  // INITIAL: play, penalised first
  EXPECT_EQ(gc->state().state, gc::State::Playing);
  EXPECT_EQ(gc->state().penalty, gc::Penalty::Manual);
  gc->chestButton(now);
  EXPECT_FALSE(gc->state().penalised());
  gc->chestButton(now);
  EXPECT_TRUE(gc->state().penalised());
  // With a GameController the button does nothing.
  ASSERT_EQ(deliver(gcPacket(2, team(12), team(34))), 1);
  gc->chestButton(now);
  EXPECT_EQ(gc->state().state, gc::State::Set);
  EXPECT_FALSE(gc->state().penalised());
  EXPECT_TRUE(logged("chest button ignored"));
}

TEST(GameController, NoTeamIgnoresPackets) {
  std::vector<std::string> log;
  GameController::Config c;
  c.port = 0;
  c.bindAddress = "127.0.0.1";
  GameController g(c, [&](const std::string& l) { log.push_back(l); });
  const auto p = gcPacket(3, team(12), team(34));
  EXPECT_FALSE(g.handlePacket(p.data(), p.size(), 1));
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("no --team"), std::string::npos);
  GameController::Config bad = c;
  bad.bindAddress = "not-an-ip";
  EXPECT_THROW(GameController(bad, [](const std::string&) {}), Error);
}

// ---- buttons -------------------------------------------------------------------------------
struct Buttons : ::testing::Test {
  ButtonInterface b;
  double t = 0;
  std::vector<ButtonEvent> run(std::initializer_list<int> pressed, double seconds) {
    std::array<double, NumTouch> touch{};
    for (int i : pressed) touch[static_cast<std::size_t>(i)] = 1;
    std::vector<ButtonEvent> events;
    for (double end = t + seconds; t < end - 1e-9; t += 0.012)
      for (ButtonEvent e : b.update(touch, t).events) events.push_back(e);
    return events;
  }
};

TEST_F(Buttons, ChestAloneIsAPressOnRelease) {
  EXPECT_TRUE(run({ChestButton}, 0.2).empty());
  EXPECT_EQ(run({}, 0.1), std::vector<ButtonEvent>{ButtonEvent::ChestPress});
  EXPECT_TRUE(run({}, 1).empty());
}

TEST_F(Buttons, CalibrationCombinationsNeedOneSecond) {
  EXPECT_TRUE(run({ChestButton, HeadFront}, 0.9).empty());
  EXPECT_EQ(run({ChestButton, HeadFront}, 0.3), std::vector<ButtonEvent>{ButtonEvent::StartCalibration});
  EXPECT_TRUE(run({ChestButton, HeadFront}, 2).empty());  // once per hold
  EXPECT_TRUE(run({}, 0.1).empty());                       // no chest press: the head was touched
  EXPECT_EQ(run({ChestButton, HeadRear}, 1.1), std::vector<ButtonEvent>{ButtonEvent::StartCalibrationEvaluation});
  EXPECT_TRUE(run({}, 0.1).empty());
  EXPECT_TRUE(run({ChestButton, HeadRear}, 0.5).empty());  // released too early
  EXPECT_TRUE(run({}, 0.1).empty());
}

TEST_F(Buttons, AllHeadButtonsUnstiffen) {
  EXPECT_TRUE(run({HeadFront, HeadMiddle}, 2).empty());
  EXPECT_EQ(run({HeadFront, HeadMiddle, HeadRear}, 1.05), std::vector<ButtonEvent>{ButtonEvent::Unstiffen});
  EXPECT_TRUE(run({}, 0.1).empty());
}

TEST_F(Buttons, AHeadTapIsOneHeadButtonBrieflyAlone) {
  for (int button : {HeadFront, HeadMiddle, HeadRear}) {
    EXPECT_TRUE(run({button}, 0.2).empty());  // fires on release
    EXPECT_EQ(run({}, 0.1), std::vector<ButtonEvent>{ButtonEvent::HeadTap}) << button;
  }
  EXPECT_TRUE(run({HeadMiddle}, 0.024).empty());  // a bounce, shorter than 0.05 s
  EXPECT_TRUE(run({}, 0.1).empty());
  EXPECT_TRUE(run({HeadMiddle}, 1.2).empty());  // held: no tap
  EXPECT_TRUE(run({}, 0.1).empty());
  EXPECT_TRUE(run({HeadFront, HeadMiddle}, 0.2).empty());  // two at once
  EXPECT_TRUE(run({}, 0.1).empty());
  // The calibration combinations are no taps, and a chest press during one is no tap either.
  EXPECT_TRUE(run({ChestButton, HeadFront}, 0.9).empty());  // held 0.9 s: nothing at all
  EXPECT_TRUE(run({}, 0.1).empty());
  EXPECT_EQ(run({ChestButton, HeadFront}, 1.1), std::vector<ButtonEvent>{ButtonEvent::StartCalibration});
  EXPECT_TRUE(run({}, 0.1).empty());
  EXPECT_TRUE(run({HeadRear}, 0.1).empty());
  EXPECT_TRUE(run({HeadRear, ChestButton}, 0.1).empty());
  EXPECT_TRUE(run({}, 0.1).empty());
}

TEST(ChestColour, FollowsTheRules) {
  GameState s;
  EXPECT_EQ(chestColour(s), (std::array<double, 3>{0, 0, 0}));
  s.state = gc::State::Ready;
  EXPECT_EQ(chestColour(s), (std::array<double, 3>{0, 0, 1}));
  s.state = gc::State::Set;
  EXPECT_EQ(chestColour(s), (std::array<double, 3>{1, 1, 0}));
  s.state = gc::State::Playing;
  EXPECT_EQ(chestColour(s), (std::array<double, 3>{0, 1, 0}));
  s.penalty = gc::Penalty::PlayerPushing;
  EXPECT_EQ(chestColour(s), (std::array<double, 3>{1, 0, 0}));
}

}  // namespace
}  // namespace nao
