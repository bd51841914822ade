// lola_peer: stands in for the NAO's LoLA daemon. A separate process that listens on a real
// Unix socket, starts the real `nao-soccer run --backend nao --cameras none`, and speaks the
// documented msgpack packets (../shared/reference/nao-v6.md) with its own encoder and decoder
// -- nothing of robot/nao/ is linked -- at LoLA's 12 ms rate. A small servo model answers the
// joint commands with measured angles. It checks every answer (keys, array lengths, types,
// LoLA joint order), the stiffness ramps, going soft in place on a corrupt packet, a fall, a
// stale stream, a closed socket and SIGTERM/SIGINT/--seconds, the buttons (with the calibration
// challenge's: its modes and the head tap), the GameController
// (packets built byte by byte on UDP, chest LED, return packets) and the answer latency.
//
// usage: lola_peer --nao-soccer BIN [--cycles N] [--json FILE]
//        lola_peer --nao-soccer BIN --soak SECONDS [--cameras files:DIR] [--arg PROGRAM_ARG]... [--emulated]
//                  [--record FILE]
//        lola_peer --nao-soccer BIN --replay FILE --answers FILE [--cameras files:DIR] [--arg PROGRAM_ARG]...
// (--cameras: the program's, default none; --arg: words added to the soak or replay run's command
// line; --emulated: the program runs under an emulator, its answer times are measured, not
// judged; --record: every sensor packet the soak sends, length-prefixed; --replay: those packets
// one at a time, each after the last one's answer, to a program in --lockstep, whose answers go
// to --answers as text, one line per packet, for comparing two programs.)
// Exit 0 when every check passed; the figures go to stdout (JSON) and the failures to stderr.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <msgpack.hpp>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

#include "tests/support/LolaWire.h"
#include "tests/support/StallProbe.h"

namespace {

using namespace lola_wire;

std::string camerasArg = "none";       // --cameras: the program's --cameras
std::vector<std::string> programArgs;  // --arg: more words for the program (the soak run's)
bool emulated = false;  // --emulated: the program runs under an emulator (--prefix qemu-x86_64 ...)
StallProbe* stallProbe = nullptr;  // the machine's own stalls, while the runs go
std::FILE* recordFile = nullptr;  // --record: the packets sent, each after its 4-byte length (host order)

// ---- the simulated robot ------------------------------------------------------------------
struct Robot {
  Sensors s;
  std::array<double, kJoints> lastMeasured{};
  Robot() {
    // Sitting-like start, every joint a distinct value so that a permutation shows.
    for (int i = 0; i < kJoints; ++i) s.position[i] = 0.2 * std::sin(1.7 * i) + 0.001 * i;
    s.position[joint("LKneePitch")] += 1.2;
    s.position[joint("RKneePitch")] += 1.2;
    s.position[joint("LHipPitch")] -= 0.7;
    s.position[joint("RHipPitch")] -= 0.7;
    s.position[joint("LAnklePitch")] -= 0.5;
    s.position[joint("RAnklePitch")] -= 0.5;
    s.position[joint("LShoulderPitch")] += 1.3;
    s.position[joint("RShoulderPitch")] += 1.3;
    s.position[joint("LElbowYaw")] -= 1.3;
    s.position[joint("RElbowYaw")] += 1.3;
    for (int i = 0; i < kJoints; ++i) {
      s.position[i] = std::clamp(s.position[i], lowerLimit(i) + 0.02, upperLimit(i) - 0.02);
      s.temperature[i] = 30 + 0.1 * i;
    }
  }
  // One 12 ms step of a position servo per joint: stiffness scales how far it tracks.
  void step(const Answer& a) {
    const auto& cmd = a["Position"];
    const auto& st = a["Stiffness"];
    for (int i = 0; i < kJoints; ++i) {
      if (!std::isfinite(cmd[i]) || !std::isfinite(st[i])) continue;
      s.position[i] += 0.5 * st[i] * (cmd[i] - s.position[i]);
      s.stiffness[i] = st[i];
      s.current[i] = 0.1 * st[i];
    }
  }
  std::string packet(Damage d = Damage::None) {
    // The client only knows what was sent in a valid packet.
    if (d == Damage::None) lastMeasured = s.position;
    return encodeSensors(s, d);
  }
};

// Position == the last measured angles (float32 on the wire), stiffness all 0.
bool softInPlace(const Answer& a, const std::array<double, kJoints>& measured, const std::string& what) {
  bool ok = true;
  const auto& st = a["Stiffness"];
  const auto& p = a["Position"];
  for (int i = 0; i < kJoints; ++i) {
    ok &= st[i] == 0;
    ok &= std::abs(p[i] - measured[i]) < 1e-5;
  }
  double worst = 0;
  for (int i = 0; i < kJoints; ++i) worst = std::max(worst, std::abs(p[i] - measured[i]));
  return check(ok, what + fmt(": not soft in place (max stiffness %.3f, position off by %.5f rad)", a.maxStiffness(), worst));
}

// ---- GameController packets, byte by byte (protocols.md, v18, 118 bytes) -----------------
struct Gc {
  int state = 0, setPlay = 0, kickingTeam = 255;
  int penaltyOfPlayer3 = 0;
  int version = 18;
  int teams[2] = {12, 34};
  uint8_t number = 0;
  std::vector<uint8_t> bytes() {
    std::vector<uint8_t> b;
    b.reserve(118);
    auto u8 = [&](int v) { b.push_back(static_cast<uint8_t>(v)); };
    auto u16 = [&](int v) { u8(v & 0xff); u8((v >> 8) & 0xff); };
    for (char c : {'R', 'G', 'm', 'e'}) u8(c);
    u8(version);
    u8(number++);
    u8(7);      // playersPerTeam
    u8(0);      // competitionPhase
    u8(0);      // competitionType
    u8(0);      // gamePhase
    u8(state);  // state
    u8(setPlay);
    u8(1);  // firstHalf
    u8(kickingTeam);
    u16(600);  // secsRemaining
    u16(0);    // secondaryTime
    for (int t = 0; t < 2; ++t) {
      u8(teams[t]);
      u8(t == 0 ? 0 : 1);  // fieldPlayerColour
      u8(2);               // goalkeeperColour
      u8(1);               // goalkeeper
      u8(t == 0 ? 2 : 1);  // score
      u8(0);               // penaltyShot
      u16(0);              // singleShots
      u16(1200);           // messageBudget
      for (int p = 1; p <= 20; ++p) {
        u8(t == 0 && p == 3 ? penaltyOfPlayer3 : 0);
        u8(t == 0 && p == 3 && penaltyOfPlayer3 ? 30 : 0);
      }
    }
    return b;
  }
};

int udpSocket(uint16_t port, uint16_t* bound) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(port);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) < 0) {
    std::perror("lola_peer: bind udp");
    std::exit(2);
  }
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  *bound = ntohs(a.sin_port);
  return fd;
}

void sendUdp(int fd, uint16_t port, const std::vector<uint8_t>& b) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only, always
  to.sin_port = htons(port);
  ::sendto(fd, b.data(), b.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
}

// ---- one cycle and figures ----------------------------------------------------------------
struct Figures {
  std::vector<double> latencyMs;  // normal cycles only
  int late = 0, missing = 0, cycles = 0, answers = 0;
  int lateOutsideNormal = 0;  // answers after 12 ms in the fault and stop phases (not judged)
  int peerBehind = 0;         // times the peer itself woke more than a cycle late
  int lateInStalls = 0;       // late answers while the machine itself stalled (tests/support/StallProbe.h)
  int rampCycles = -1;        // main run: answers from the first (soft) one to stiffness 1
  int fallSoftAfter = -1;     // cycles from the first fallen packet to a soft answer
  double staleFirstMs = -1;   // ms from the last packet to the first unsolicited soft answer
  int staleSoftAnswers = 0;   // soft answers during the 300 ms of silence
  double closedExitMs = -1;   // ms from LoLA closing the socket to the program's exit
};
Figures figures;
int tolerateExtras = 0;  // cycles in which an unsolicited (stale-time) soft answer may still arrive

// Sends one packet at the tick and waits for its answer until the next tick.
// measureLatency: part of the normal-load figures.
bool cycle(Peer& peer, Robot& robot, double& tick, Answer& a, Damage damage = Damage::None,
           bool measureLatency = false) {
  sleepUntil(tick);
  // The peer itself may be held up by a busy machine: then it goes on from now, one packet at
  // a time, instead of sending the packets it missed in a burst (LoLA never does).
  if (monotonic() - tick > kCycle) {
    tick = monotonic();
    ++figures.peerBehind;
  }
  // Nothing may be waiting: the program answers each packet once (and on its own only while
  // the stream is stale, which the stale phase reads itself).
  Answer extra;
  while (peer.next(extra, monotonic() - 1)) {
    if (tolerateExtras > 0) softInPlace(extra, robot.lastMeasured, "a late stale-time answer");
    else check(false, "an answer nobody asked for (cycle " + std::to_string(figures.cycles) + ")");
  }
  if (tolerateExtras > 0) --tolerateExtras;
  const std::string bytes = robot.packet(damage);
  if (recordFile) {
    const auto n = static_cast<uint32_t>(bytes.size());
    std::fwrite(&n, sizeof n, 1, recordFile);
    std::fwrite(bytes.data(), 1, bytes.size(), recordFile);
  }
  const double sent = monotonic();
  peer.send(bytes);
  ++figures.cycles;
  tick += kCycle;
  // Wait a whole cycle after sending and then 100 ms more, so that a late answer is measured
  // as late, not lost (and not mistaken for an answer nobody asked for in the next cycle).
  const bool got = peer.next(a, std::max(tick, sent + kCycle) + 0.1);
  if (got) {
    ++figures.answers;
    const double latencyMs = (a.time - sent) * 1000;
    if (!measureLatency && latencyMs > kCycle * 1000) ++figures.lateOutsideNormal;
    if (measureLatency) {
      figures.latencyMs.push_back(latencyMs);
      if (latencyMs > kCycle * 1000) {
        ++figures.late;
        // Under an emulator (--emulated) the times are measured, not judged; nor is an answer
        // late while the machine itself stalled (the probe was held up too).
        if (stallProbe && stallProbe->stalledDuring(sent, a.time)) {
          ++figures.lateInStalls;
          std::fprintf(stderr, "lola_peer: answer %.0f came after %.2f ms, while the machine itself stalled\n",
                       static_cast<double>(figures.cycles), latencyMs);
        } else {
          check(emulated, fmt("answer %.0f came after %.2f ms, later than the 12 ms cycle", figures.cycles, latencyMs));
        }
      }
    }
    if (damage == Damage::None) robot.step(a);
  } else if (measureLatency) {
    ++figures.late;
    ++figures.missing;
    check(false, "no answer to cycle " + std::to_string(figures.cycles));
  }
  return got;
}

// Runs cycles until the stiffness is back at the program's 1.0, checking that it ramps:
// starting near 0, never dropping, at most one ramp step (12 ms / 1 s) per cycle.
void expectRamp(Peer& peer, Robot& robot, double& tick, int maxCycles, const std::string& what) {
  Answer a;
  double previous = -1;
  int n = 0;
  bool started = false;
  for (; n < maxCycles; ++n) {
    if (!cycle(peer, robot, tick, a, Damage::None, false)) continue;
    const double s = a.maxStiffness();
    if (!started && s == 0) continue;  // still soft (recovery time)
    if (!started) {
      started = true;
      check(s <= 0.0125 + 1e-6, what + fmt(": the ramp starts at %.3f, not near 0", s));
    } else {
      check(s + 1e-6 >= previous, what + fmt(": stiffness dropped from %.3f to %.3f", previous, s));
      check(s - previous <= 0.0125 + 1e-6, what + fmt(": stiffness jumped by %.3f in one cycle", s - previous));
    }
    previous = s;
    if (s >= 0.999) break;
  }
  check(started && previous >= 0.999, what + fmt(": stiffness reached only %.3f after %.0f cycles", previous, n));
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }


struct Run {
  std::string dir, socket;
  int listener = -1, fd = -1;
  Child child;
};

Run start(const std::string& bin, const std::string& dir, const std::string& name, std::vector<std::string> extra) {
  Run r;
  r.dir = dir;
  r.socket = dir + "/" + name + ".sock";
  r.listener = listenOn(r.socket);
  // The socket's path as the program sees it (inside --chroot's root).
  const std::string socket = r.socket.substr(chrootDir.size());
  std::vector<std::string> args = prefix;
  const bool ownCameras = std::find(extra.begin(), extra.end(), "--cameras") != extra.end();
  for (const std::string& a : {bin, std::string("run"), std::string("--backend"), std::string("nao"),
                               std::string("--lola-socket"), socket})
    args.push_back(a);
  if (!ownCameras) args.insert(args.end(), {"--cameras", camerasArg});
  args.insert(args.end(), extra.begin(), extra.end());
  r.child = spawn(args, dir + "/" + name + ".stderr");
  r.fd = acceptClient(r.listener, r.child);
  return r;
}

// ---- scenarios ---------------------------------------------------------------------------

// The main run: normal cycles with the GameController, then a corrupt packet, a fall, a stale
// stream and a closed socket.
void mainRun(const std::string& bin, const std::string& dir, int normalCycles, int& returnPackets) {
  uint16_t gcPort = 0, returnPort = 0;
  {
    const int probe = udpSocket(0, &gcPort);  // a free port for the program's receiver
    ::close(probe);
  }
  const int returnFd = udpSocket(0, &returnPort);
  const int gcFd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  Run run = start(bin, dir, "main",
                  {"--team", "12", "--player", "3", "--gc-address", "127.0.0.1", "--gc-port", std::to_string(gcPort),
                   "--gc-return-port", std::to_string(returnPort), "--json", dir + "/main.json"});
  Peer peer(run.fd, run.child);
  Robot robot;
  double tick = monotonic() + 0.05;
  Answer a, previous;

  // 1. Start: the first answer is soft in place, then the stiffness ramps; normal load.
  check.phase = "normal";
  Gc gc;
  // The GameController script: cycle -> what to send; the chest LED expected afterwards.
  struct Step {
    int cycle;
    std::function<void()> change;
    std::array<double, 3> chest;
    const char* name;
  };
  std::vector<Step> script = {
      {150, [&] { gc.state = 0; }, {0, 0, 0}, "INITIAL"},
      {240, [&] { gc.state = 1; }, {0, 0, 1}, "READY"},
      {330, [&] { gc.state = 2; }, {1, 1, 0}, "SET"},
      {420, [&] { gc.state = 3; }, {0, 1, 0}, "PLAYING"},
      {510, [&] { gc.penaltyOfPlayer3 = 2; }, {1, 0, 0}, "penalised (pushing)"},
      {600, [&] { gc.penaltyOfPlayer3 = 0; }, {0, 1, 0}, "unpenalised"},
      {690, [&] { gc.state = 4; }, {0, 0, 0}, "FINISHED"},
  };
  std::size_t nextStep = 0;
  const Step* expectStep = nullptr;
  int rampCycles = -1;
  double previousMax = 0;
  for (int c = 0; c < normalCycles; ++c) {
    if (nextStep < script.size() && c == script[nextStep].cycle) {
      script[nextStep].change();
      sendUdp(gcFd, gcPort, gc.bytes());
      expectStep = &script[nextStep++];
    } else if (c >= 150 && c % 40 == 0) {
      sendUdp(gcFd, gcPort, gc.bytes());  // the GameController's 2 Hz
    }
    // Packets the program must reject (logged, no effect on the game state).
    if (c == 280) {
      Gc v17 = gc;
      v17.version = 17;
      v17.state = 3;
      auto b = v17.bytes();
      b.resize(116);
      sendUdp(gcFd, gcPort, b);
    }
    if (c == 290) {
      auto b = gc.bytes();
      b.resize(60);
      b[10] = 3;
      sendUdp(gcFd, gcPort, b);
    }
    if (c == 300) {
      Gc others = gc;
      others.teams[0] = 5;
      others.teams[1] = 6;
      others.state = 3;
      sendUdp(gcFd, gcPort, others.bytes());
    }
    if (!cycle(peer, robot, tick, a, Damage::None, true)) continue;
    const double s = a.maxStiffness();
    if (c == 0) {
      softInPlace(a, robot.lastMeasured, "first answer");
    } else {
      check(s + 1e-6 >= previousMax, fmt("cycle %.0f: stiffness dropped from %.3f to %.3f", c, previousMax, s));
      check(s - previousMax <= 0.0125 + 1e-6, fmt("cycle %.0f: stiffness jumped by %.3f (no ramp)", c, s - previousMax));
      double step = 0;
      for (int i = 0; i < kJoints; ++i) step = std::max(step, std::abs(a["Position"][i] - previous["Position"][i]));
      check(step <= 0.05, fmt("cycle %.0f: a position target jumped by %.3f rad", c, step));
    }
    for (int j = 0; j < kJoints; ++j)
      check(a["Position"][j] >= lowerLimit(j) - 1e-3 && a["Position"][j] <= upperLimit(j) + 1e-3,
            std::string(kLolaOrder[j]) + fmt(" target %.3f outside its limits %.3f..%.3f (LoLA order?)", a["Position"][j],
                                             lowerLimit(j), upperLimit(j)));
    if (rampCycles < 0 && s >= 0.999) rampCycles = c;
    if (c == 325) {  // the v17, truncated and other teams' packets (280..300) changed nothing
      const auto& chest = a["Chest"];
      check(chest.size() == 3 && chest[0] == 0 && chest[1] == 0 && chest[2] == 1,
            "a rejected GameController packet changed the game state (chest no longer READY blue)");
    }
    previousMax = s;
    previous = a;
    // The chest LED follows the game state 25 cycles (300 ms) after each change.
    if (expectStep && c == expectStep->cycle + 25) {
      const auto& chest = a["Chest"];
      check(chest.size() == 3 && std::abs(chest[0] - expectStep->chest[0]) < 1e-6 &&
                std::abs(chest[1] - expectStep->chest[1]) < 1e-6 && std::abs(chest[2] - expectStep->chest[2]) < 1e-6,
            std::string("chest LED does not show ") + expectStep->name + fmt(" (%.1f %.1f %.1f)", chest[0], chest[1], chest[2]));
    }
  }
  figures.rampCycles = rampCycles;
  check(rampCycles >= 60 && rampCycles <= 100,
        fmt("the stiffness should take about 1 s (83 cycles) to reach 1, took %.0f cycles", rampCycles));
  // LoLA order: a NAO's stand, whatever its exact angles, is left/right symmetric with bent
  // knees, hips and ankles pitched back and arms down; joints in the wrong slots break that.
  const auto& pos = a["Position"];
  auto at = [&](const char* name) { return pos[joint(name)]; };
  for (const auto& [l, r, sign] : std::vector<std::tuple<const char*, const char*, double>>{
           {"LHipPitch", "RHipPitch", 1}, {"LKneePitch", "RKneePitch", 1}, {"LAnklePitch", "RAnklePitch", 1},
           {"LShoulderPitch", "RShoulderPitch", 1}, {"LHipRoll", "RHipRoll", -1}, {"LAnkleRoll", "RAnkleRoll", -1},
           {"LShoulderRoll", "RShoulderRoll", -1}, {"LElbowYaw", "RElbowYaw", -1}, {"LElbowRoll", "RElbowRoll", -1}})
    check(std::abs(at(l) - sign * at(r)) < 0.02,
          std::string(l) + fmt(" %.3f and ", at(l)) + r + fmt(" %.3f are not mirrored in the stand", at(r)));
  check(at("LKneePitch") > 0.2 && at("RKneePitch") > 0.2, "the stand's knees are not bent (KneePitch)");
  check(at("LHipPitch") < -0.1 && at("LAnklePitch") < -0.1, "the stand's HipPitch/AnklePitch do not pitch back");
  check(at("LShoulderPitch") > 0.8, "the stand's arms are not down (ShoulderPitch)");

  // Return packets: 32 bytes, documented layout, this robot's numbers.
  for (;;) {
    uint8_t b[256];
    const ssize_t n = ::recv(returnFd, b, sizeof b, MSG_DONTWAIT);
    if (n < 0) break;
    ++returnPackets;
    check(n == 32, "return packet of " + std::to_string(n) + " bytes");
    if (n != 32) continue;
    float f[6];
    std::memcpy(f, b + 8, sizeof f);
    check(std::memcmp(b, "RGrt", 4) == 0 && b[4] == 4 && b[5] == 3 && b[6] == 12 && b[7] == 0,
          "return packet header/version/player/team/fallen wrong");
    check(f[3] == -1.0f, "return packet ballAge should be -1 (never seen)");
  }
  check(returnPackets >= 4, "only " + std::to_string(returnPackets) + " return packets in " +
                                std::to_string(normalCycles * kCycle) + " s");

  // 2. Corrupt packets: each answered soft in place, named in the log; then recovery + ramp.
  check.phase = "corrupt";
  for (Damage d : {Damage::BadMsgpack, Damage::ShortPosition, Damage::NanGyroscope, Damage::StringAccelerometer,
                   Damage::MissingTouch}) {
    if (cycle(peer, robot, tick, a, d)) softInPlace(a, robot.lastMeasured, "answer to a corrupt packet");
    else check(false, "no answer to a corrupt packet");
    if (cycle(peer, robot, tick, a)) softInPlace(a, robot.lastMeasured, "good packet right after a corrupt one");
  }
  expectRamp(peer, robot, tick, 400, "after the corrupt packets");

  // 3. A fall: the program's fall detector, then the backend's safety: soft in place.
  check.phase = "fall";
  robot.s.angles = {1.2, 0.1};
  robot.s.fsr.fill(0);
  int softAfter = -1;
  for (int c = 0; c < 60; ++c) {
    if (!cycle(peer, robot, tick, a)) continue;
    if (softAfter < 0 && a.maxStiffness() == 0) softAfter = c;
    if (softAfter >= 0) softInPlace(a, robot.lastMeasured, "while fallen");
  }
  figures.fallSoftAfter = softAfter;
  check(softAfter >= 0 && softAfter <= 3, fmt("soft %.0f cycles after the fall", softAfter));
  robot.s.angles = {0, 0};
  robot.s.fsr.fill(0.6);
  expectRamp(peer, robot, tick, 500, "after the fall");

  // 4. A stale stream: no packet for 300 ms. The program answers soft in place on its own.
  check.phase = "stale";
  const double silentFrom = peer.lastSend();
  const double silentUntil = silentFrom + 0.3;
  std::vector<Answer> unsolicited;
  while (monotonic() < silentUntil) {
    if (peer.next(a, silentUntil)) unsolicited.push_back(a);
  }
  if (check(unsolicited.size() >= 10, "only " + std::to_string(unsolicited.size()) + " soft answers in 300 ms of silence")) {
    const double first = (unsolicited.front().time - silentFrom) * 1000;
    figures.staleFirstMs = first;
    figures.staleSoftAnswers = static_cast<int>(unsolicited.size());
    check(first >= 30 && first <= 120, fmt("the first soft answer came %.0f ms after the last packet", first));
    for (const auto& u : unsolicited) softInPlace(u, robot.lastMeasured, "while the stream is stale");
  }
  tick = monotonic() + 0.002;
  tolerateExtras = 3;  // a soft answer the program timed out for may cross the next packet
  if (cycle(peer, robot, tick, a)) softInPlace(a, robot.lastMeasured, "first packet after the stale period");
  expectRamp(peer, robot, tick, 400, "after the stale stream");

  // 5. LoLA closes the socket (its writing side): the program sends a last soft packet and ends.
  check.phase = "closed";
  for (int c = 0; c < 20; ++c) cycle(peer, robot, tick, a);
  const double closedAt = monotonic();
  ::shutdown(run.fd, SHUT_WR);
  Answer last;
  bool gotLast = false;
  while (peer.next(a, monotonic() + 2.0)) {
    last = a;
    gotLast = true;
  }
  figures.closedExitMs = (monotonic() - closedAt) * 1000;  // the program's end closes its side
  if (check(gotLast, "no last packet after LoLA closed the socket")) softInPlace(last, robot.lastMeasured, "last packet");
  check(run.child.exited(5000), "the program did not exit after LoLA closed the socket");
  check(run.child.exitCode() == 1, "exit code after a closed socket: " + std::to_string(run.child.exitCode()) + ", expected 1");

  const std::string log = run.child.stderrText();
  for (const char* expected :
       {"going soft in place: corrupt LoLA packet: LoLA sensor packet: not valid msgpack",
        "corrupt LoLA packet: LoLA sensor packet: Position: expected an array of 25 numbers, got an array of 24",
        "corrupt LoLA packet: LoLA sensor packet: Gyroscope[1]: not a finite number",
        "corrupt LoLA packet: LoLA sensor packet: Accelerometer[0]: expected a number, got a string",
        "corrupt LoLA packet: LoLA sensor packet: Touch: missing", "going soft in place: fall: fallen",
        "going soft in place: stale sensor data: no LoLA packet for more than", "LoLA closed the socket",
        "gamecontroller: rejected GameController packet: version 17 arrived, this program speaks version 18",
        "gamecontroller: rejected GameController packet: length 60 bytes",
        "gamecontroller: rejected GameController packet: for teams 5 and 6, we are team 12", "game: READY",
        "game: penalised (pushing)", "game: FINISHED", "lola: body P0000074A04S8C700011"})
    check(contains(log, expected), std::string("the log lacks '") + expected + "'");
  ::close(run.fd);
  ::close(run.listener);
  ::close(returnFd);
  ::close(gcFd);
}

// Until the program ends after a stop: every answer soft in place, at least two of them, and
// the program exits.
void expectSoftStop(Peer& peer, Robot& robot, double& tick, Run& run) {
  Answer a;
  int soft = 0;
  for (int c = 0; c < 400 && !peer.eof(); ++c) {
    if (!cycle(peer, robot, tick, a)) {
      if (run.child.exited(0)) break;
      continue;
    }
    if (a.maxStiffness() == 0) {
      ++soft;
      softInPlace(a, robot.lastMeasured, "stopping");
    } else {
      check(soft == 0, "stiff again after going soft for the stop");
    }
  }
  check(soft >= 2, "only " + std::to_string(soft) + " soft answers before the program ended");
  check(run.child.exited(5000), "the program did not exit");
}

// SIGTERM / SIGINT / --seconds: the run ends softly (soft in place, reason logged, exit 0).
// The SIGTERM run also holds the head buttons (unstiffen) and presses the chest (stiffen).
void stopRun(const std::string& bin, const std::string& dir, const std::string& how) {
  check.phase = how;
  std::vector<std::string> extra;
  if (how == "seconds") extra = {"--seconds", "2"};
  // The SIGINT run's voice: a stand-in text-to-speech command that writes what it is told.
  const std::string said = dir + "/said.txt";
  const bool speech = how == "SIGINT" && chrootDir.empty();
  if (speech) {
    const std::string say = dir + "/say.sh";
    std::ofstream(say) << "#!/bin/sh\nprintf '%s\\n' \"$*\" >> '" << said << "'\n";
    ::chmod(say.c_str(), 0755);
    // The camera shield on: dark frames, so that cognition (and with it the behaviour, which
    // speaks) runs as on a robot whose cameras are covered.
    const std::string shield = dir + "/shield";
    for (const auto& [camera, width, height] : {std::tuple{"top", 640, 480}, std::tuple{"bottom", 320, 240}}) {
      ::mkdir(shield.c_str(), 0755);
      const std::string folder = shield + "/" + camera;
      ::mkdir(folder.c_str(), 0755);
      const std::vector<unsigned char> dark(static_cast<std::size_t>(width) * height * 3, 12);
      check(stbi_write_png((folder + "/dark.png").c_str(), width, height, 3, dark.data(), width * 3) != 0,
            "cannot write the shield's frame");
    }
    extra = {"--speech-command", say, "--cameras", "files:" + shield};
  }
  Run run = start(bin, dir, how, extra);
  Peer peer(run.fd, run.child);
  Robot robot;
  double tick = monotonic() + 0.05;
  Answer a;
  expectRamp(peer, robot, tick, 200, how + " run start");
  if (how == "SIGTERM") {
    check.phase = "buttons";
    robot.s.touch[kHeadFront] = robot.s.touch[kHeadMiddle] = robot.s.touch[kHeadRear] = 1;
    int softAfter = -1;
    for (int c = 0; c < 110; ++c)
      if (cycle(peer, robot, tick, a) && softAfter < 0 && a.maxStiffness() == 0) softAfter = c;
    check(softAfter >= 80 && softAfter <= 90, fmt("the head buttons unstiffened after %.0f cycles (1 s = 84)", softAfter));
    robot.s.touch[kHeadFront] = robot.s.touch[kHeadMiddle] = robot.s.touch[kHeadRear] = 0;
    for (int c = 0; c < 100; ++c)
      if (cycle(peer, robot, tick, a)) softInPlace(a, robot.lastMeasured, "unstiffened, waiting for the chest button");
    robot.s.touch[kChest] = 1;
    for (int c = 0; c < 10; ++c) cycle(peer, robot, tick, a);
    robot.s.touch[kChest] = 0;
    expectRamp(peer, robot, tick, 200, "after the chest button");
    check.phase = how;
  }
  if (how == "SIGINT") {
    // The calibration challenge's referee: chest + head front held 1.2 s (calibration mode), a
    // head tap, chest + head rear held 1.2 s (evaluation mode); the robot stays stiff.
    check.phase = "challenge buttons";
    auto hold = [&](std::initializer_list<int> touched, int cycles) {
      for (int t : touched) robot.s.touch[t] = 1;
      for (int c = 0; c < cycles; ++c)
        if (cycle(peer, robot, tick, a)) check(a.maxStiffness() > 0.5, "the robot went soft during the challenge's buttons");
      for (int t : touched) robot.s.touch[t] = 0;
    };
    hold({kChest, kHeadFront}, 100);
    hold({}, 20);
    hold({kHeadMiddle}, 15);
    hold({}, 20);
    hold({kChest, kHeadRear}, 100);
    hold({}, 20);
    check.phase = how;
  }
  if (how == "SIGTERM" || how == "SIGINT") {
    for (int c = 0; c < 30; ++c) cycle(peer, robot, tick, a);
    kill(run.child.pid, how == "SIGTERM" ? SIGTERM : SIGINT);
  }
  expectSoftStop(peer, robot, tick, run);
  check(run.child.exitCode() == 0, "exit code " + std::to_string(run.child.exitCode()) + " after " + how + ", expected 0");
  const std::string log = run.child.stderrText();
  const std::string expected = how == "seconds" ? "going soft in place: stopping: --seconds 2 reached"
                                                : "going soft in place: " + how + " received: stopping";
  check(contains(log, expected), "the log lacks '" + expected + "'");
  if (how == "SIGTERM")
    for (const char* e : {"buttons: all head buttons (unstiffen)", "going soft in place: head buttons held",
                          "safety: resuming (chest button)"})
      check(contains(log, e), std::string("the log lacks '") + e + "'");
  if (how == "SIGINT")
    for (const char* e : {"buttons: chest + head front (start calibration)", "challenge: calibration mode",
                          "buttons: head tap", "buttons: chest + head rear (start the calibration evaluation)",
                          "challenge: evaluation mode"})
      check(contains(log, e), std::string("the log lacks '") + e + "'");
  if (speech) {  // each mode acknowledged aloud, in order, through the command
    std::ifstream in(said);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    check(text == "Calibration mode\nEvaluation mode\n", "the speech command was told '" + text + "'");
    check(contains(log, "speech: Calibration mode") && contains(log, "speech: Evaluation mode"),
          "the log lacks the speech lines");
  }
  ::close(run.fd);
  ::close(run.listener);
}

// --soak SECONDS (the robot bundle's proof in a root of its own): the ramp, then SECONDS of
// normal cycles, every answer judged against the 12 ms cycle, then SIGTERM: soft in place until
// the program ends with exit 0.
void soakRun(const std::string& bin, const std::string& dir, double seconds) {
  check.phase = "soak";
  Run run = start(bin, dir, "soak", programArgs);
  Peer peer(run.fd, run.child);
  Robot robot;
  double tick = monotonic() + 0.05;
  Answer a;
  expectRamp(peer, robot, tick, 200, "soak start");
  const int cycles = static_cast<int>(seconds / kCycle + 0.5);
  for (int c = 0; c < cycles && !peer.eof(); ++c) cycle(peer, robot, tick, a, Damage::None, true);
  check(!peer.eof(), "the program closed the socket during the soak");
  kill(run.child.pid, SIGTERM);
  expectSoftStop(peer, robot, tick, run);
  check(run.child.exitCode() == 0, "exit code " + std::to_string(run.child.exitCode()) + " after SIGTERM, expected 0");
  const std::string log = run.child.stderrText();
  check(contains(log, "going soft in place: SIGTERM received: stopping"), "the log lacks the soft stop on SIGTERM");
  if (!check.failures.empty()) std::fprintf(stderr, "lola_peer: the program's stderr:\n%s\n", log.c_str());
  ::close(run.fd);
  ::close(run.listener);
}

// --replay FILE --answers FILE: the recorded packets, one at a time, each sent once the last
// one's answer has come (the program runs with --lockstep); each answer as a line of text
// (its keys in order, every value as the float it was on the wire). Then LoLA goes away.
void replayRun(const std::string& bin, const std::string& dir, const std::string& packetsFile,
               const std::string& answersFile) {
  check.phase = "replay";
  std::vector<std::string> packets;
  {
    std::ifstream in(packetsFile, std::ios::binary);
    check(static_cast<bool>(in), "cannot read " + packetsFile);
    uint32_t n = 0;
    while (in.read(reinterpret_cast<char*>(&n), sizeof n)) {
      std::string b(n, '\0');
      if (!in.read(b.data(), n)) break;
      packets.push_back(std::move(b));
    }
  }
  if (!check(!packets.empty(), "no packets in " + packetsFile)) return;
  Run run = start(bin, dir, "replay", programArgs);
  Peer peer(run.fd, run.child);
  std::ofstream out(answersFile);
  Answer a;
  std::size_t answered = 0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    peer.send(packets[i]);
    // The first answer waits for the program's build; under a sanitizer a cycle is slow.
    if (!check(peer.next(a, monotonic() + (i == 0 ? 120 : 30)), "no answer to packet " + std::to_string(i))) break;
    ++answered;
    out << i;
    for (const auto& [key, values] : a.values) {
      out << ' ' << key;
      char number[32];
      for (double v : values) {
        std::snprintf(number, sizeof number, " %.9g", v);
        out << number;
      }
    }
    out << " Sonar";
    for (bool b : a.sonar) out << ' ' << b;
    out << '\n';
  }
  check(answered == packets.size(), "answered " + std::to_string(answered) + " of " + std::to_string(packets.size()));
  ::close(run.fd);  // LoLA goes away: the program ends
  if (!check(run.child.exited(60000), "the program did not end after LoLA's socket closed")) kill(run.child.pid, SIGKILL);
  if (!check.failures.empty()) std::fprintf(stderr, "lola_peer: the program's stderr:\n%s\n", run.child.stderrText().c_str());
  ::close(run.listener);
  std::fprintf(stderr, "lola_peer: replayed %zu packets, %zu answers to %s\n", packets.size(), answered, answersFile.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::string bin, json, record, replay, answers;
  int cycles = 1000;
  double soak = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--nao-soccer" && i + 1 < argc) bin = argv[++i];
    else if (a == "--cycles" && i + 1 < argc) cycles = std::atoi(argv[++i]);
    else if (a == "--json" && i + 1 < argc) json = argv[++i];
    else if (a == "--soak" && i + 1 < argc) soak = std::atof(argv[++i]);
    else if (a == "--chroot" && i + 1 < argc) chrootDir = argv[++i];
    else if (a == "--prefix" && i + 1 < argc) prefix.push_back(argv[++i]);
    else if (a == "--cameras" && i + 1 < argc) camerasArg = argv[++i];
    else if (a == "--arg" && i + 1 < argc) programArgs.push_back(argv[++i]);
    else if (a == "--emulated") emulated = true;
    else if (a == "--record" && i + 1 < argc) record = argv[++i];
    else if (a == "--replay" && i + 1 < argc) replay = argv[++i];
    else if (a == "--answers" && i + 1 < argc) answers = argv[++i];
    else {
      std::fprintf(stderr,
                   "usage: lola_peer --nao-soccer BIN [--cycles N] [--json FILE]\n"
                   "       lola_peer --nao-soccer BIN --soak SECONDS [--chroot ROOT] [--prefix ARG]... [--json FILE]\n"
                   "                 [--cameras none|files:DIR] [--arg PROGRAM_ARG]... [--emulated] [--record FILE]\n"
                   "       lola_peer --nao-soccer BIN --replay FILE --answers FILE [--cameras none|files:DIR]\n"
                   "                 [--arg PROGRAM_ARG]...\n");
      return 2;
    }
  }
  if (bin.empty() || cycles < 800) {
    std::fprintf(stderr, "lola_peer: --nao-soccer BIN is required, --cycles >= 800\n");
    return 2;
  }
  signal(SIGPIPE, SIG_IGN);
  if (const int parentExit = runInAHighPrioritySession("lola_peer"); parentExit >= 0) return parentExit;
  StallProbe probe;
  stallProbe = &probe;
  const std::string dir = mkWorkDir();
  int returnPackets = 0;
  if (!replay.empty()) {
    if (answers.empty()) {
      std::fprintf(stderr, "lola_peer: --replay needs --answers FILE\n");
      return 2;
    }
    replayRun(bin, dir, replay, answers);
  } else if (soak > 0) {
    if (!record.empty() && !(recordFile = std::fopen(record.c_str(), "wb"))) {
      std::fprintf(stderr, "lola_peer: cannot write %s\n", record.c_str());
      return 2;
    }
    soakRun(bin, dir, soak);
    if (recordFile) std::fclose(recordFile);
  } else {
    mainRun(bin, dir, cycles, returnPackets);
    stopRun(bin, dir, "SIGTERM");
    stopRun(bin, dir, "SIGINT");
    stopRun(bin, dir, "seconds");
  }

  auto& l = figures.latencyMs;
  std::sort(l.begin(), l.end());
  const double maxMs = l.empty() ? 0 : l.back();
  const double p99 = l.empty() ? 0 : l[static_cast<std::size_t>(0.99 * (l.size() - 1))];
  const double median = l.empty() ? 0 : l[(l.size() - 1) / 2];
  double mean = 0;
  for (double v : l) mean += v / static_cast<double>(l.size());
  std::ostringstream out;
  out << "{\"cycles_total\": " << figures.cycles << ", \"answers\": " << figures.answers
      << ", \"normal_cycles\": " << l.size() + figures.missing << ", \"late_answers\": " << figures.late
      << ", \"max_answer_ms\": " << maxMs << ", \"p99_answer_ms\": " << p99 << ", \"median_answer_ms\": " << median
      << ", \"mean_answer_ms\": " << mean << ", \"ramp_cycles\": " << figures.rampCycles
      << ", \"ramp_ms\": " << figures.rampCycles * kCycle * 1000 << ", \"fall_soft_after_cycles\": " << figures.fallSoftAfter
      << ", \"stale_first_soft_ms\": " << figures.staleFirstMs << ", \"stale_soft_answers\": " << figures.staleSoftAnswers
      << ", \"closed_exit_ms\": " << figures.closedExitMs << ", \"late_outside_normal\": " << figures.lateOutsideNormal
      << ", \"peer_behind\": " << figures.peerBehind << ", \"late_in_machine_stalls\": " << figures.lateInStalls
      << ", \"machine_stalls\": " << probe.figures().dump()
      << ", \"return_packets\": " << returnPackets << ", \"checks_passed\": " << check.passed
      << ", \"checks_failed\": " << check.failures.size() << ", \"work_dir\": \"" << dir << "\"}\n";
  std::fputs(out.str().c_str(), stdout);
  if (!json.empty()) std::ofstream(json) << out.str();
  if (check.failures.empty() && !std::getenv("LOLA_PEER_KEEP")) {
    // Keep the program's logs only when something failed (or LOLA_PEER_KEEP is set).
    std::system(("rm -rf '" + dir + "'").c_str());
  }
  return check.failures.empty() ? 0 : 1;
}
