#include "scenarios/GameControllerLink.h"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "robot/Error.h"

namespace nao::sim {

GameControllerLink::GameControllerLink(std::uint16_t port) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw Error("--gc-port", std::string("socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw Error("--gc-port", "cannot bind UDP port " + std::to_string(port) + ": " + why);
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
}

GameControllerLink::~GameControllerLink() {
  if (fd_ >= 0) ::close(fd_);
}

int GameControllerLink::receive(const Handler& handle) {
  int count = 0;
  for (int i = 0; i < 64; ++i) {  // at 2 Hz a handful at most; bounded against a flood
    std::uint8_t buffer[1024];
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer, sizeof buffer, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
    if (n < 0) break;
    handle(buffer, static_cast<std::size_t>(n), from);
    ++count;
  }
  return count;
}

}  // namespace nao::sim
