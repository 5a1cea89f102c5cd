#pragma once
// The FCI's TCP side for a client (fci_session.hpp): requests out, and a reader thread that files
// every response by its command id, for the caller that waits for it. Not real-time.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>

#include "comply/franka/fci_protocol.hpp"

namespace comply::franka {

struct FciResponse {
  fci::Command command = fci::Command::kConnect;
  std::uint8_t status = 0;
  std::uint16_t version = 0;  ///< Connect's
};

class FciCommandChannel {
 public:
  /// Connects within `timeout_s`; throws hardware::BackendError naming the address.
  FciCommandChannel(const std::string& address, std::uint16_t port, double timeout_s);
  ~FciCommandChannel();
  FciCommandChannel(const FciCommandChannel&) = delete;
  FciCommandChannel& operator=(const FciCommandChannel&) = delete;

  /// Sends one request with `payload` (its size the command's); returns its command id. Throws
  /// hardware::BackendError when the connection is gone.
  std::uint32_t send(fci::Command command, std::span<const std::uint8_t> payload);
  /// The same without throwing: no id when it could not be sent.
  std::optional<std::uint32_t> trySend(fci::Command command,
                                       std::span<const std::uint8_t> payload) noexcept;
  /// The next response to `command_id` (Move has two: started, then finished), waiting up to
  /// `timeout_s`; false when none came or the connection closed (closed() then).
  bool await(std::uint32_t command_id, double timeout_s, FciResponse& response);
  /// The next response to `command_id` if one is in.
  bool take(std::uint32_t command_id, FciResponse& response);
  /// Any thread, without a lock (the control thread asks every cycle).
  [[nodiscard]] bool closed() const noexcept { return closed_.load(std::memory_order_acquire); }
  /// The robot's address as this connection sees it (IPv4, network order).
  [[nodiscard]] std::uint32_t peerAddress() const noexcept { return peer_address_; }

 private:
  void readResponses(const std::stop_token& stop);

  int socket_ = -1;
  std::uint32_t peer_address_ = 0;
  std::uint32_t next_id_ = 0;
  std::mutex send_mutex_;
  mutable std::mutex mutex_;
  std::condition_variable filed_;
  std::map<std::uint32_t, std::deque<FciResponse>> responses_;
  std::atomic<bool> closed_{false};
  std::jthread reader_;
};

}  // namespace comply::franka
