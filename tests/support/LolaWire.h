#pragma once
// The LoLA side of the wire for the project's stand-ins for the NAO's LoLA daemon (lola_peer,
// sim_lola_peer): the documented msgpack packets (../shared/reference/nao-v6.md) with an encoder
// and decoder of their own -- nothing of robot/nao/ -- the checks they keep, the program they
// start as a child and the Unix socket it connects to. Header-only: each peer is one file.
#include <fcntl.h>
#include <poll.h>
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
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <msgpack.hpp>

namespace lola_wire {

// ---- the documented format, typed out from nao-v6.md (not taken from robot/) -------------
constexpr int kJoints = 25;
const std::array<const char*, kJoints> kLolaOrder = {
    "HeadYaw",        "HeadPitch",     "LShoulderPitch", "LShoulderRoll", "LElbowYaw",      "LElbowRoll",
    "LWristYaw",      "LHipYawPitch",  "LHipRoll",       "LHipPitch",     "LKneePitch",     "LAnklePitch",
    "LAnkleRoll",     "RHipRoll",      "RHipPitch",      "RKneePitch",    "RAnklePitch",    "RAnkleRoll",
    "RShoulderPitch", "RShoulderRoll", "RElbowYaw",      "RElbowRoll",    "RWristYaw",      "LHand",
    "RHand"};
inline int joint(const std::string& name) {
  for (int i = 0; i < kJoints; ++i)
    if (name == kLolaOrder[i]) return i;
  std::fprintf(stderr, "lola_peer: unknown joint %s\n", name.c_str());
  std::exit(2);
}
// Joint limits in LoLA order (deg; hands 0..1), nao-v6.md.
const std::array<std::pair<double, double>, kJoints> kLimitsDeg = {{
    {-119.5, 119.5}, {-38.5, 29.5}, {-119.5, 119.5}, {-18, 76}, {-119.5, 119.5}, {-88.5, -2}, {-104.5, 104.5},
    {-65.62, 42.44}, {-21.74, 45.29}, {-88, 27.73}, {-5.29, 121.04}, {-68.15, 52.86}, {-22.79, 44.06},
    {-45.29, 21.74}, {-88, 27.73}, {-5.90, 121.47}, {-67.97, 53.40}, {-44.06, 22.80},
    {-119.5, 119.5}, {-76, 18}, {-119.5, 119.5}, {2, 88.5}, {-104.5, 104.5}, {0, 1}, {0, 1}}};
inline double lowerLimit(int j) { return j >= 23 ? kLimitsDeg[j].first : kLimitsDeg[j].first * M_PI / 180; }
inline double upperLimit(int j) { return j >= 23 ? kLimitsDeg[j].second : kLimitsDeg[j].second * M_PI / 180; }
const std::map<std::string, std::size_t> kActuatorLengths = {
    {"Position", 25}, {"Stiffness", 25}, {"Chest", 3}, {"LEar", 10}, {"REar", 10}, {"LEye", 24},
    {"REye", 24},     {"LFoot", 3},      {"RFoot", 3}, {"Skull", 12}, {"Sonar", 2}};
constexpr double kCycle = 0.012;
// Touch indices (documented order): chest, head front, head middle, head rear, ...
constexpr int kChest = 0, kHeadFront = 1, kHeadMiddle = 2, kHeadRear = 3;

inline double monotonic() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

inline void sleepUntil(double t) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t);
  ts.tv_nsec = static_cast<long>((t - static_cast<double>(ts.tv_sec)) * 1e9);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// ---- checks -----------------------------------------------------------------------------
struct Checks {
  int passed = 0;
  std::vector<std::string> failures;
  std::string phase = "start";
  bool operator()(bool ok, const std::string& what) {
    if (ok) {
      ++passed;
    } else if (failures.size() < 60) {
      failures.push_back(phase + ": " + what);
      std::fprintf(stderr, "lola_peer: FAILED %s: %s\n", phase.c_str(), what.c_str());
    }
    return ok;
  }
};
inline Checks check;

inline std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char s[256];
  std::snprintf(s, sizeof s, f, a, b, c);
  return s;
}

// ---- sensor packets ---------------------------------------------------------------------
struct Sensors {
  std::array<double, kJoints> position{}, stiffness{}, current{}, temperature{};
  std::array<int, kJoints> status{};
  std::array<double, 3> accelerometer{0, 0, -9.81}, gyroscope{};
  std::array<double, 2> angles{};
  std::array<double, 4> battery{0.9, 0, -1.2, 30};  // charge, status, current, temperature
  std::array<double, 8> fsr{0.6, 0.6, 0.6, 0.6, 0.6, 0.6, 0.6, 0.6};
  std::array<double, 14> touch{};
  std::array<double, 2> sonar{2.5, 2.5};
  std::array<std::string, 4> robotConfig{"P0000074A04S8C700011", "6.0.0", "P0000073A07S8AF00027", "6.0.0"};
};

enum class Damage { None, BadMsgpack, ShortPosition, NanGyroscope, StringAccelerometer, MissingTouch };

using Packer = msgpack::packer<msgpack::sbuffer>;
inline void key(Packer& pk, const char* k) {
  pk.pack_str(static_cast<uint32_t>(std::strlen(k)));
  pk.pack_str_body(k, static_cast<uint32_t>(std::strlen(k)));
}
// LoLA sends float32 (0xca) for every number but Status; msgpack-c's pack_float would write
// whole numbers as integers, so the bytes are written here.
inline void float32(Packer& pk, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  const char b[5] = {static_cast<char>(0xca), static_cast<char>(bits >> 24), static_cast<char>(bits >> 16),
                     static_cast<char>(bits >> 8), static_cast<char>(bits)};
  pk.pack_str_body(b, 5);  // raw bytes into the stream
}
template <class A>
inline void floats(Packer& pk, const char* k, const A& a, std::size_t n = 0) {
  key(pk, k);
  const std::size_t count = n ? n : a.size();
  pk.pack_array(static_cast<uint32_t>(count));
  for (std::size_t i = 0; i < count; ++i) float32(pk, static_cast<float>(a[i]));
}

inline std::string encodeSensors(const Sensors& s, Damage damage = Damage::None) {
  if (damage == Damage::BadMsgpack) return std::string("\xc1\xc1\x00garbage-not-msgpack", 21);
  msgpack::sbuffer buffer;
  Packer pk(buffer);
  pk.pack_map(damage == Damage::MissingTouch ? 12 : 13);
  floats(pk, "Position", s.position, damage == Damage::ShortPosition ? 24 : 0);
  floats(pk, "Stiffness", s.stiffness);
  floats(pk, "Current", s.current);
  floats(pk, "Temperature", s.temperature);
  key(pk, "Status");
  pk.pack_array(kJoints);
  for (int v : s.status) pk.pack_int(v);
  if (damage == Damage::StringAccelerometer) {
    key(pk, "Accelerometer");
    pk.pack_array(3);
    for (int i = 0; i < 3; ++i) pk.pack(std::string("9.81"));
  } else {
    floats(pk, "Accelerometer", s.accelerometer);
  }
  if (damage == Damage::NanGyroscope) {
    auto g = s.gyroscope;
    g[1] = std::nan("");
    floats(pk, "Gyroscope", g);
  } else {
    floats(pk, "Gyroscope", s.gyroscope);
  }
  floats(pk, "Angles", s.angles);
  floats(pk, "Battery", s.battery);
  floats(pk, "FSR", s.fsr);
  if (damage != Damage::MissingTouch) floats(pk, "Touch", s.touch);
  floats(pk, "Sonar", s.sonar);
  key(pk, "RobotConfig");
  pk.pack_array(4);
  for (const auto& c : s.robotConfig) pk.pack(c);
  return std::string(buffer.data(), buffer.size());
}

// ---- answers ----------------------------------------------------------------------------
struct Answer {
  double time = 0;  // monotonic s when the peer read it
  std::map<std::string, std::vector<double>> values;
  std::vector<bool> sonar;
  const std::vector<double>& operator[](const char* k) const {
    static const std::vector<double> none(kJoints, std::nan(""));
    auto it = values.find(k);
    return it == values.end() ? none : it->second;
  }
  double maxStiffness() const {
    const auto& s = (*this)["Stiffness"];
    return *std::max_element(s.begin(), s.end());
  }
};

// Checks one answer against the documented actuator map; returns false when unusable.
inline bool validate(const msgpack::object& o, Answer& a) {
  if (!check(o.type == msgpack::type::MAP, "answer is not a msgpack map")) return false;
  std::set<std::string> keys;
  bool ok = true;
  for (uint32_t i = 0; i < o.via.map.size; ++i) {
    const auto& kv = o.via.map.ptr[i];
    if (!check(kv.key.type == msgpack::type::STR, "answer key is not a string")) return false;
    const std::string k(kv.key.via.str.ptr, kv.key.via.str.size);
    keys.insert(k);
    auto len = kActuatorLengths.find(k);
    ok &= check(len != kActuatorLengths.end(), "undocumented key '" + k + "' in the answer");
    if (len == kActuatorLengths.end()) continue;
    if (!check(kv.val.type == msgpack::type::ARRAY && kv.val.via.array.size == len->second,
               k + ": not an array of " + std::to_string(len->second)))
      return false;
    for (uint32_t j = 0; j < kv.val.via.array.size; ++j) {
      const auto& e = kv.val.via.array.ptr[j];
      if (k == "Sonar") {
        ok &= check(e.type == msgpack::type::BOOLEAN, "Sonar[" + std::to_string(j) + "] is not a boolean");
        a.sonar.push_back(e.type == msgpack::type::BOOLEAN && e.via.boolean);
        continue;
      }
      // LoLA reads floats: an integer 0 or 1 in its place is a wrong type.
      double v = std::nan("");
      if (e.type == msgpack::type::FLOAT32 || e.type == msgpack::type::FLOAT64) v = e.via.f64;
      ok &= check(e.type == msgpack::type::FLOAT32, k + "[" + std::to_string(j) + "] is not a float32");
      ok &= check(std::isfinite(v), k + "[" + std::to_string(j) + "] is not a finite number");
      if (k != "Position") ok &= check(v >= 0 && v <= 1, k + "[" + std::to_string(j) + "] outside 0..1");
      a.values[k].push_back(v);
    }
  }
  ok &= check(keys.size() == kActuatorLengths.size(), "answer has " + std::to_string(keys.size()) + " of the " +
                                                        std::to_string(kActuatorLengths.size()) + " documented keys");
  return ok && keys.size() == kActuatorLengths.size();
}

// ---- the child and its socket -------------------------------------------------------------
struct Child {
  pid_t pid = -1;
  int status = -1;
  std::string log;
  bool reaped = false;
  bool exited(int waitMs) {
    const double end = monotonic() + waitMs / 1000.0;
    for (;;) {
      if (reaped) return true;
      if (waitpid(pid, &status, WNOHANG) == pid) reaped = true;
      if (reaped) return true;
      if (monotonic() > end) return false;
      usleep(2000);
    }
  }
  int exitCode() const { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }
  std::string stderrText() const {
    std::ifstream f(log);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
};

// --chroot ROOT: the program runs in ROOT (a root holding nothing but the robot bundle, or an
// older OS), its socket in ROOT/tmp; --prefix ARG...: words before the program (its loader).
inline std::string chrootDir;
inline std::vector<std::string> prefix;

inline Child spawn(const std::vector<std::string>& args, const std::string& log) {
  Child c;
  c.log = log;
  c.pid = fork();
  if (c.pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1);
    if (!chrootDir.empty() && (::chroot(chrootDir.c_str()) != 0 || ::chdir("/") != 0)) {
      std::perror("chroot");
      _exit(127);
    }
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    std::perror("execv");
    _exit(127);
  }
  return c;
}

class Peer {
 public:
  Peer(int fd, Child& child) : fd_(fd), child_(child) {
    const int one = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one);
  }

  void send(const std::string& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
      if (n <= 0) {
        // The program may just have ended (a stop); the phases check what they expect.
        if (errno != EPIPE && errno != ECONNRESET) check(false, std::string("send failed: ") + std::strerror(errno));
        eof_ = true;
        return;
      }
      done += static_cast<std::size_t>(n);
    }
    lastSend_ = monotonic();
  }

  // The next answer, waiting until `deadline` (monotonic s). False on timeout or EOF.
  bool next(Answer& a, double deadline) {
    for (;;) {
      msgpack::object_handle oh;
      try {
        if (unpacker_.next(oh)) {
          a = Answer{};
          a.time = monotonic();
          validate(oh.get(), a);
          return true;
        }
      } catch (const std::exception& e) {
        check(false, std::string("the client's bytes are not msgpack: ") + e.what());
        return false;
      }
      const int left = static_cast<int>(std::ceil((deadline - monotonic()) * 1000));
      if (eof_) return false;
      pollfd p{fd_, POLLIN, 0};  // a past deadline still takes what has arrived
      if (::poll(&p, 1, std::max(0, left)) <= 0) return false;
      unpacker_.reserve_buffer(4096);
      const ssize_t n = ::recv(fd_, unpacker_.buffer(), 4096, 0);
      if (n <= 0) {
        eof_ = true;
        return false;
      }
      unpacker_.buffer_consumed(static_cast<std::size_t>(n));
    }
  }

  int fd() const { return fd_; }
  bool eof() const { return eof_; }
  double lastSend() const { return lastSend_; }
  Child& child() { return child_; }

 private:
  int fd_;
  Child& child_;
  msgpack::unpacker unpacker_;
  bool eof_ = false;
  double lastSend_ = 0;
};

inline std::string mkWorkDir() {
  std::string pattern = chrootDir + "/tmp/lola_peer.XXXXXX";
  if (!chrootDir.empty()) ::mkdir((chrootDir + "/tmp").c_str(), 01777);
  std::vector<char> tmpl(pattern.begin(), pattern.end());
  tmpl.push_back('\0');
  if (!mkdtemp(tmpl.data())) {
    std::perror("mkdtemp");
    std::exit(2);
  }
  return std::string(tmpl.data());
}

inline int listenOn(const std::string& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
  ::unlink(path.c_str());
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0 || ::listen(fd, 1) < 0) {
    std::perror("lola_peer: listen");
    std::exit(2);
  }
  return fd;
}

inline int acceptClient(int listener, Child& child) {
  pollfd p{listener, POLLIN, 0};
  if (::poll(&p, 1, 30000) <= 0) {
    child.exited(0);
    std::fprintf(stderr, "lola_peer: nao-soccer did not connect; its stderr:\n%s\n", child.stderrText().c_str());
    kill(child.pid, SIGKILL);
    std::exit(1);
  }
  return ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
}

// LoLA runs at a high priority on the robot; here the peer and the program it starts (which
// inherits it) get a larger CPU share than builds that may share the machine, so that a late
// answer means a slow program, not a busy machine. Without the permission: as is.
// With autogroup scheduling (Linux's default on desktops and these machines) a nice value
// only counts inside its session, and every session gets an equal share: so the work runs in
// a session of its own whose group gets the higher priority, and the calling process waits for
// it. Returns -1 in the session (go on), the session's exit code in the caller, 2 on failure.
inline int runInAHighPrioritySession(const char* name) {
  const pid_t parent = getpid();
  const pid_t worker = fork();
  if (worker < 0) {
    std::perror(name);
    return 2;
  }
  if (worker > 0) {
    int status = 0;
    while (waitpid(worker, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  prctl(PR_SET_PDEATHSIG, SIGKILL);  // a test driver that kills the caller kills the work too
  if (getppid() != parent) _exit(1);
  setsid();
  if (FILE* group = std::fopen("/proc/self/autogroup", "w")) {
    std::fputs("-10", group);
    std::fclose(group);
  }
  if (setpriority(PRIO_PROCESS, 0, -10) != 0) std::fprintf(stderr, "%s: running at normal priority\n", name);
  return -1;
}

}  // namespace lola_wire
