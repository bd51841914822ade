#pragma once
// The client end of LoLA's Unix stream socket: connect (LoLA may start after us), split the
// byte stream into msgpack objects, write answers without ever blocking a cycle for long.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace nao::lola {

class LolaClient {
 public:
  explicit LolaClient(std::string path);
  ~LolaClient();
  LolaClient(const LolaClient&) = delete;
  LolaClient& operator=(const LolaClient&) = delete;

  // Connects, retrying every 100 ms for up to timeout seconds while cancelled() is false.
  // Throws nao::Error(path, why) when no LoLA answers.
  void connect(double timeout, const std::function<bool()>& cancelled = {});

  enum class Read { Packet, Corrupt, Timeout, Closed, Interrupted };
  // Waits up to timeoutMs for the next complete msgpack object (its bytes in `packet`).
  // Corrupt: bytes that can never be msgpack arrived (`error` says why); they were dropped.
  // Closed: LoLA closed the socket or it failed (`error` says how). Interrupted: a signal.
  Read read(std::vector<std::uint8_t>& packet, int timeoutMs, std::string& error);
  // True when a complete object is already buffered (the program is behind LoLA).
  bool packetBuffered() const;
  // Writes one answer; false with `error` when the socket is gone or LoLA has not read
  // for a whole cycle.
  bool write(const std::vector<std::uint8_t>& bytes, std::string& error);
  void close();

  const std::string& path() const { return path_; }
  bool connected() const { return fd_ >= 0; }

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace nao::lola
