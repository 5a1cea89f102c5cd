// The FCI's TCP side for a client (fci_command_channel.hpp).

#include "fci_command_channel.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include "comply/franka/fci_stream.hpp"
#include "comply/hardware/backend.hpp"
#include "comply/hardware/tcp_connect.hpp"

namespace comply::franka {
namespace {

int connectWithin(const std::string& address, std::uint16_t port, double timeout_s,
                  std::uint32_t& peer) {
  std::string why;
  const int socket = hardware::connectTcp(address, port, timeout_s, why);
  if (socket < 0) {
    throw hardware::BackendError("cannot connect to the Franka robot at " + address + ":" +
                                 std::to_string(port) + ": " + why +
                                 " (is FCI activated in Desk, and the address the robot's, not "
                                 "its Desk's?)");
  }
  const int one = 1;
  (void)::setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  in_addr robot{};
  (void)::inet_pton(AF_INET, address.c_str(), &robot);
  peer = robot.s_addr;
  return socket;
}

}  // namespace

FciCommandChannel::FciCommandChannel(const std::string& address, std::uint16_t port,
                                     double timeout_s)
    : socket_(connectWithin(address, port, timeout_s, peer_address_)) {
  reader_ = std::jthread([this](const std::stop_token& stop) { readResponses(stop); });
}

FciCommandChannel::~FciCommandChannel() {
  reader_ = {};
  ::close(socket_);
}

std::uint32_t FciCommandChannel::send(fci::Command command, std::span<const std::uint8_t> payload) {
  const std::lock_guard lock(send_mutex_);
  std::vector<std::uint8_t> message(fci::kHeaderBytes + payload.size());
  const std::uint32_t id = next_id_++;
  fci::putHeader(std::span<std::uint8_t, fci::kHeaderBytes>(message.data(), fci::kHeaderBytes),
                 {command, id, static_cast<std::uint32_t>(message.size())});
  std::copy(payload.begin(), payload.end(), message.begin() + fci::kHeaderBytes);
  std::size_t sent = 0;
  while (sent < message.size()) {
    const ssize_t wrote =
        ::send(socket_, message.data() + sent, message.size() - sent, MSG_NOSIGNAL);
    if (wrote <= 0) {
      if (wrote < 0 && errno == EINTR) {
        continue;
      }
      throw hardware::BackendError(std::string("the Franka robot's command connection closed "
                                               "while sending ") +
                                   fci::commandName(command));
    }
    sent += static_cast<std::size_t>(wrote);
  }
  return id;
}

std::optional<std::uint32_t> FciCommandChannel::trySend(
    fci::Command command, std::span<const std::uint8_t> payload) noexcept {
  try {
    return send(command, payload);
  } catch (...) {
    return std::nullopt;
  }
}

void FciCommandChannel::readResponses(const std::stop_token& stop) {
  std::array<std::uint8_t, fci::kHeaderBytes> header_bytes{};
  std::vector<std::uint8_t> payload;
  while (!stop.stop_requested()) {
    if (!readExactly(socket_, header_bytes.data(), header_bytes.size(), stop)) {
      break;
    }
    const fci::Header header = fci::getHeader(header_bytes);
    if (header.size < fci::kHeaderBytes || header.size > 65536) {
      break;  // out of step: nothing after it can be read
    }
    payload.resize(header.size - fci::kHeaderBytes);
    if (!readExactly(socket_, payload.data(), payload.size(), stop)) {
      break;
    }
    FciResponse response;
    response.command = header.command;
    response.status = payload.empty() ? 0xff : payload[0];
    if (header.command == fci::Command::kConnect && payload.size() >= 3) {
      std::memcpy(&response.version, payload.data() + 1, sizeof response.version);
    }
    const std::lock_guard lock(mutex_);
    responses_[header.command_id].push_back(response);
    filed_.notify_all();
  }
  const std::lock_guard lock(mutex_);
  closed_.store(true, std::memory_order_release);
  filed_.notify_all();
}

bool FciCommandChannel::take(std::uint32_t command_id, FciResponse& response) {
  const std::lock_guard lock(mutex_);
  auto found = responses_.find(command_id);
  if (found == responses_.end() || found->second.empty()) {
    return false;
  }
  response = found->second.front();
  found->second.pop_front();
  return true;
}

bool FciCommandChannel::await(std::uint32_t command_id, double timeout_s, FciResponse& response) {
  std::unique_lock lock(mutex_);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    auto found = responses_.find(command_id);
    if (found != responses_.end() && !found->second.empty()) {
      response = found->second.front();
      found->second.pop_front();
      return true;
    }
    if (closed_.load(std::memory_order_acquire) ||
        filed_.wait_until(lock, deadline) == std::cv_status::timeout) {
      found = responses_.find(command_id);
      if (found != responses_.end() && !found->second.empty()) {
        continue;
      }
      return false;
    }
  }
}

}  // namespace comply::franka
