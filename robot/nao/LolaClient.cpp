#include "robot/nao/LolaClient.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "robot/Error.h"
#include "robot/nao/LolaPacket.h"

namespace nao::lola {

LolaClient::LolaClient(std::string path) : path_(std::move(path)) {}

LolaClient::~LolaClient() { close(); }

void LolaClient::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  buffer_.clear();
}

void LolaClient::connect(double timeout, const std::function<bool()>& cancelled) {
  close();
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path_.empty() || path_.size() >= sizeof addr.sun_path)
    throw Error("--lola-socket", "'" + path_ + "' is not a usable Unix socket path");
  std::memcpy(addr.sun_path, path_.c_str(), path_.size() + 1);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  int lastErrno = 0;
  for (;;) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw Error(path_, std::string("socket: ") + std::strerror(errno));
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) {
      fd_ = fd;
      return;
    }
    lastErrno = errno;
    ::close(fd);
    if (cancelled && cancelled()) throw Error(path_, "interrupted while waiting for LoLA");
    if (std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  throw Error(path_, std::string("cannot connect to LoLA (") + std::strerror(lastErrno) +
                         "; is lola running and naoqi stopped?)");
}

bool LolaClient::packetBuffered() const {
  try {
    return objectLength(buffer_.data(), buffer_.size()) > 0;
  } catch (const Error&) {
    return true;  // the next read reports it
  }
}

LolaClient::Read LolaClient::read(std::vector<std::uint8_t>& packet, int timeoutMs, std::string& error) {
  if (fd_ < 0) {
    error = "not connected";
    return Read::Closed;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeoutMs);
  for (;;) {
    std::size_t length = 0;
    try {
      length = objectLength(buffer_.data(), buffer_.size());
    } catch (const Error& e) {
      error = e.what();
      buffer_.clear();  // resynchronise on the next write LoLA makes
      return Read::Corrupt;
    }
    if (length > 0) {
      packet.assign(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(length));
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(length));
      return Read::Packet;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd_, POLLIN, 0};
    const int n = ::poll(&p, 1, static_cast<int>(std::max<long long>(0, left.count())));
    if (n < 0) {
      if (errno == EINTR) return Read::Interrupted;
      error = std::string("poll: ") + std::strerror(errno);
      return Read::Closed;
    }
    if (n == 0) return Read::Timeout;
    std::uint8_t chunk[4096];
    const ssize_t got = ::recv(fd_, chunk, sizeof chunk, MSG_DONTWAIT);
    if (got == 0) {
      error = "LoLA closed the socket";
      return Read::Closed;
    }
    if (got < 0) {
      if (errno == EINTR) return Read::Interrupted;
      if (errno == EAGAIN || errno == EWOULDBLOCK) continue;
      error = std::string("LoLA socket failed: ") + std::strerror(errno);
      return Read::Closed;
    }
    buffer_.insert(buffer_.end(), chunk, chunk + got);
  }
}

bool LolaClient::write(const std::vector<std::uint8_t>& bytes, std::string& error) {
  if (fd_ < 0) {
    error = "not connected";
    return false;
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      // LoLA's side of the socket is full. An unstarted answer may wait one cycle; a started
      // one must be finished, since half a map would corrupt the stream.
      const auto limit = std::chrono::milliseconds(done == 0 ? 12 : 100);
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(limit - (Clock::now() - start));
      if (left.count() <= 0) {
        if (done == 0) {
          error = "LoLA is not reading: answer dropped";
        } else {
          error = "LoLA stopped reading in the middle of an answer";
          close();
        }
        return false;
      }
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, static_cast<int>(left.count()));
      continue;
    }
    error = std::string("writing to LoLA failed: ") + (n < 0 ? std::strerror(errno) : "no progress");
    close();
    return false;
  }
  return true;
}

}  // namespace nao::lola
