// match --gc udp (scenarios/GameControllerLink.h): an external GameController, here a peer in
// the test sending v18 packets over UDP on loopback, runs the game. The match follows the
// peer's states, score and penalty, both robots hear its packets and answer with return
// packets, a corrupt datagram is logged and ignored, and no packet at all fails the match
// with the port named instead of hanging.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "robot/Error.h"
#include "robot/nao/GameController.h"
#include "scenarios/Match.h"

namespace {

using Clock = std::chrono::steady_clock;

// A UDP socket on 127.0.0.1 (port 0: any free one).
int udpSocket(std::uint16_t port, std::uint16_t* bound) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  if (bound) *bound = ntohs(addr.sin_port);
  return fd;
}

std::uint16_t freePort() {
  std::uint16_t port = 0;
  ::close(udpSocket(0, &port));
  return port;
}

TEST(MatchUdp, AnExternalGameControllerRunsTheGame) {
  std::uint16_t returnPort = 0;
  const int peer = udpSocket(0, &returnPort);  // the GameController: sends from and hears on this port
  const std::uint16_t gcPort = freePort();
  std::atomic<bool> done{false};
  std::set<int> returnTeams;
  int returns = 0;
  std::thread gameController([&] {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(gcPort);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    nao::gc::GameControlData d;
    d.playersPerTeam = 1;
    d.teams[0].teamNumber = 5;
    d.teams[1].teamNumber = 6;
    d.teams[1].fieldPlayerColour = 1;
    d.secsRemaining = 300;
    Clock::time_point heard{};  // the first return packet: the match is playing
    bool corruptSent = false;
    while (!done) {
      std::uint8_t buffer[256];
      while (true) {
        const ssize_t n = ::recv(peer, buffer, sizeof buffer, MSG_DONTWAIT);
        if (n < 0) break;
        try {
          returnTeams.insert(nao::gc::parseReturnData(buffer, static_cast<std::size_t>(n)).teamNum);
          ++returns;
          if (heard == Clock::time_point{}) heard = Clock::now();
        } catch (const nao::Error&) {
          ADD_FAILURE() << "a return packet that does not decode";
        }
      }
      const double since = heard == Clock::time_point{} ? -1 : std::chrono::duration<double>(Clock::now() - heard).count();
      d.state = since < 0.5 ? nao::gc::State::Initial
                : since < 1.0 ? nao::gc::State::Ready
                : since < 1.5 ? nao::gc::State::Set
                              : nao::gc::State::Playing;
      if (since >= 2.0) d.teams[1].score = 1;
      d.teams[0].players[0].penalty =
          static_cast<std::uint8_t>(since >= 2.5 ? nao::gc::Penalty::LeavingTheField : nao::gc::Penalty::None);
      ++d.packetNumber;
      const auto bytes = nao::gc::serialize(d);
      ::sendto(peer, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
      if (since >= 0.2 && !corruptSent) {
        const std::uint8_t junk[7] = {'R', 'G', 'm', 'e', 18, 0, 0};
        ::sendto(peer, junk, sizeof junk, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
        corruptSent = true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  nao::sim::MatchOptions o;
  o.gc = "udp";
  o.gcPort = gcPort;
  o.gcReturnPort = returnPort;
  o.gcWait = 10;
  o.percepts = "oracle";
  o.seconds = 7;
  nao::sim::MatchResult r;
  EXPECT_NO_THROW(r = nao::sim::runMatch(o));
  done = true;
  gameController.join();
  ::close(peer);

  std::vector<std::string> states;
  bool rejected = false, penalty = false, removed = false;
  int heardPlaying = 0;
  for (const auto& e : r.json["events"]) {
    if (e["kind"] == "gc_state") states.push_back(e["text"]);
    rejected = rejected || e["kind"] == "gc_rejected";
    penalty = penalty || (e["kind"] == "gc_penalty" && e["team"] == "home");
    removed = removed || (e["kind"] == "place" && e.value("team", "") == "home" &&
                          e["what"].get<std::string>().find("GameController") != std::string::npos);
    heardPlaying += e["kind"] == "robot_log" && e["text"] == "game: PLAYING";
  }
  EXPECT_EQ(states, (std::vector<std::string>{"READY", "SET", "PLAYING"})) << r.json["events"].dump();
  EXPECT_EQ(r.awayScore, 1);
  EXPECT_EQ(r.homeScore, 0);
  EXPECT_TRUE(rejected) << "the corrupt datagram is logged";
  EXPECT_TRUE(penalty);
  EXPECT_TRUE(removed) << "the penalised robot is taken off";
  EXPECT_EQ(heardPlaying, 2) << "both robots' receivers took the packets";
  EXPECT_EQ(returnTeams, (std::set<int>{5, 6})) << "both robots answered";
  EXPECT_GE(returns, 4);
}

TEST(MatchUdp, NoGameControllerFailsNamingThePort) {
  nao::sim::MatchOptions o;
  o.gc = "udp";
  o.gcPort = freePort();
  o.gcReturnPort = freePort();
  o.gcWait = 1;
  o.percepts = "oracle";
  o.seconds = 30;
  try {
    nao::sim::runMatch(o);
    FAIL() << "no error";
  } catch (const nao::RunFailure& e) {  // outside the input: exit 1
    EXPECT_NE(std::string(e.what()).find("UDP port " + std::to_string(o.gcPort)), std::string::npos) << e.what();
  }
}

}  // namespace
