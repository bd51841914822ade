#pragma once
// `match --gc udp`: the network between an external GameController and a simulated game. One
// UDP socket bound to the GameController port takes the external GameController's packets; the
// match hands each datagram to both robots' receivers (as two NAOs on one broadcast would each
// get a copy), and the receivers answer from their own sockets.
#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <functional>

namespace nao::sim {

class GameControllerLink {
 public:
  using Handler = std::function<void(const std::uint8_t* data, std::size_t size, const sockaddr_in& from)>;
  // Binds 0.0.0.0:port (0: any free port). Throws nao::Error("--gc-port", why).
  explicit GameControllerLink(std::uint16_t port);
  ~GameControllerLink();
  GameControllerLink(const GameControllerLink&) = delete;
  GameControllerLink& operator=(const GameControllerLink&) = delete;
  // Hands every pending datagram to `handle`; returns how many there were.
  int receive(const Handler& handle);
  std::uint16_t port() const { return port_; }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace nao::sim
