#include "scenarios/GameControllerLink.h"

#include <sys/socket.h>
#include <unistd.h>

#include "robot/nao/GameController.h"

namespace nao::sim {

GameControllerLink::GameControllerLink(std::uint16_t port) { fd_ = gc::bindUdp("0.0.0.0", port, port_); }

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
