// A blocking RTDE client over POSIX TCP sockets (see rtde_client.hpp).

#include "comply/ur/rtde_client.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "comply/hardware/tcp_connect.hpp"

namespace comply::ur {
namespace {

using Clock = std::chrono::steady_clock;

int millisecondsUntil(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return static_cast<int>(std::max<std::int64_t>(0, left.count()));
}

Clock::time_point after(double seconds) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

RtdeClient::RtdeClient(const std::string& host, std::uint16_t port, double timeout_s)
    : timeout_s_(timeout_s) {
  const std::string where = host + ":" + std::to_string(port);
  std::string why;
  socket_ = hardware::connectTcp(host, port, timeout_s, why);
  if (socket_ < 0) {
    throw RtdeError("RTDE: cannot connect to " + where + " within " + std::to_string(timeout_s) +
                    " s: " + why);
  }
  const int on = 1;
  ::setsockopt(socket_, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  try {
    write(protocolVersionRequest());
    if (!readAccepted(await(PackageType::kRequestProtocolVersion, timeout_s_).payload)) {
      throw RtdeError("RTDE: the controller at " + where + " refused protocol version 2");
    }
  } catch (...) {
    ::close(socket_);  // no destructor runs for an object whose constructor threw
    throw;
  }
}

void RtdeClient::disconnect() noexcept {
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  if (null >= 0) {
    ::dup2(null, socket_);  // the connection closes; the number stays taken until ~RtdeClient
    ::close(null);
  }
}

RtdeClient::~RtdeClient() {
  if (socket_ >= 0) {
    ::close(socket_);
  }
}

ControllerVersion RtdeClient::controllerVersion() {
  write(controllerVersionRequest());
  return readControllerVersion(await(PackageType::kGetUrControlVersion, timeout_s_).payload);
}

Recipe RtdeClient::setupOutputs(double frequency_hz, const std::vector<std::string>& names) {
  write(setupOutputsRequest({frequency_hz, names}));
  const SetupReply reply = readSetupReply(await(PackageType::kSetupOutputs, timeout_s_).payload);
  output_ = {reply.recipe_id, names, recipeTypes(names, reply)};
  return output_;
}

Recipe RtdeClient::setupInputs(const std::vector<std::string>& names) {
  write(setupInputsRequest(names));
  const SetupReply reply = readSetupReply(await(PackageType::kSetupInputs, timeout_s_).payload);
  return {reply.recipe_id, names, recipeTypes(names, reply)};
}

void RtdeClient::start() {
  write(startRequest());
  if (!readAccepted(await(PackageType::kStart, timeout_s_).payload)) {
    throw RtdeError("RTDE: the controller refused to start" +
                    (messages_.empty() ? std::string() : ": " + messages_.back().message));
  }
}

void RtdeClient::pause() {
  write(pauseRequest());
  if (!readAccepted(await(PackageType::kPause, timeout_s_).payload)) {
    throw RtdeError("RTDE: the controller refused to pause");
  }
}

bool RtdeClient::receive(std::vector<RtdeValue>& values, double timeout_s) {
  const Clock::time_point deadline = after(timeout_s);
  Package package;
  while (next(package, std::chrono::duration<double>(deadline - Clock::now()).count())) {
    if (package.type == PackageType::kTextMessage) {
      messages_.push_back(readTextMessage(package.payload));
    } else if (package.type == PackageType::kDataPackage) {
      if (readRecipeId(package.payload) == output_.id) {
        values = readData(package.payload, output_.types);
        return true;
      }
      ++other_recipe_;
    }
  }
  return false;
}

void RtdeClient::send(const Recipe& recipe, const std::vector<RtdeValue>& values) {
  write(dataPackage(recipe.id, values));
}

void RtdeClient::write(const std::vector<std::uint8_t>& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(socket_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      throw RtdeError(std::string("RTDE: the connection to the controller is lost: ") +
                      std::strerror(errno));
    }
    sent += static_cast<std::size_t>(n);
  }
}

Package RtdeClient::await(PackageType type, double timeout_s) {
  const Clock::time_point deadline = after(timeout_s);
  Package package;
  while (next(package, std::chrono::duration<double>(deadline - Clock::now()).count())) {
    if (package.type == type) {
      return package;
    }
    if (package.type == PackageType::kTextMessage) {
      messages_.push_back(readTextMessage(package.payload));
    }
  }
  throw RtdeError(
      "RTDE: no answer of type " + std::to_string(static_cast<int>(type)) +
      " from the controller within " + std::to_string(timeout_s) + " s" +
      (messages_.empty() ? std::string() : " (it said: " + messages_.back().message + ")"));
}

bool RtdeClient::next(Package& package, double timeout_s) {
  const Clock::time_point deadline = after(std::max(0.0, timeout_s));
  while (!framer_.next(package)) {
    pollfd readable{socket_, POLLIN, 0};
    const int ready = ::poll(&readable, 1, millisecondsUntil(deadline));
    if (ready < 0 && errno == EINTR) {
      continue;
    }
    if (ready == 0) {
      return false;
    }
    std::array<std::uint8_t, 4096> buffer{};
    const ssize_t n = ::recv(socket_, buffer.data(), buffer.size(), 0);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      throw RtdeError(n == 0 ? "RTDE: the controller closed the connection"
                             : std::string("RTDE: the connection to the controller is lost: ") +
                                   std::strerror(errno));
    }
    framer_.feed(std::span(buffer.data(), static_cast<std::size_t>(n)));
  }
  return true;
}

}  // namespace comply::ur
