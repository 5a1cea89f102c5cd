#pragma once
// A client of a UR controller's RTDE interface over TCP (port 30004), blocking, as comply's UR
// backend uses it: connect, agree on protocol version 2, set up an output recipe (what to read,
// how often) and input recipes (registers to write), start, then read the controller's data
// packages and write the inputs. POSIX sockets, TCP_NODELAY; each call waits at most its timeout
// and throws RtdeError naming what failed (a refusal, the controller's text message, a timeout,
// the connection lost).

#include <cstdint>
#include <string>
#include <vector>

#include "comply/ur/rtde_packages.hpp"

namespace comply::ur {

/// A recipe as set up: its id, its variables and their types.
struct Recipe {
  std::uint8_t id = 0;
  std::vector<std::string> names;
  std::vector<RtdeType> types;
};

class RtdeClient {
 public:
  /// Connects to `host` (an IPv4 address) within `timeout_s` and agrees on protocol version 2.
  RtdeClient(const std::string& host, std::uint16_t port, double timeout_s = 2.0);
  ~RtdeClient();
  RtdeClient(const RtdeClient&) = delete;
  RtdeClient& operator=(const RtdeClient&) = delete;

  /// Closes the connection at once while its socket's number stays taken (by /dev/null) until
  /// this client goes: a thread that still writes to it fails instead of writing to whatever
  /// file would get the number next.
  void disconnect() noexcept;

  [[nodiscard]] ControllerVersion controllerVersion();
  /// The output recipe of `names` at `frequency_hz`; throws naming every variable refused.
  Recipe setupOutputs(double frequency_hz, const std::vector<std::string>& names);
  Recipe setupInputs(const std::vector<std::string>& names);
  void start();
  void pause();
  /// The next data package of the output recipe, its values in the recipe's order; false when
  /// none came within `timeout_s`. Text messages that come meanwhile are kept (messages()).
  bool receive(std::vector<RtdeValue>& values, double timeout_s);
  /// Writes `values` (the recipe's order and types) to input recipe `recipe`.
  void send(const Recipe& recipe, const std::vector<RtdeValue>& values);
  /// The connection's socket, for a thread that writes ready input packages to it itself without
  /// waiting (the UR backend's control thread); valid while this client lives.
  [[nodiscard]] int socket() const noexcept { return socket_; }
  /// Data packages received of a recipe other than the output recipe (dropped): a controller
  /// that numbers its recipes otherwise than its set-up said.
  [[nodiscard]] std::uint64_t otherRecipePackages() const noexcept { return other_recipe_; }
  /// The controller's text messages received so far.
  [[nodiscard]] const std::vector<TextMessage>& messages() const noexcept { return messages_; }

 private:
  void write(const std::vector<std::uint8_t>& bytes);
  /// The next package of `type` (text messages kept on the way); throws after `timeout_s`.
  Package await(PackageType type, double timeout_s);
  /// The next package of any type, or false after `timeout_s`.
  bool next(Package& package, double timeout_s);

  int socket_ = -1;
  double timeout_s_;
  PackageFramer framer_;
  Recipe output_;
  std::vector<TextMessage> messages_;
  std::uint64_t other_recipe_ = 0;
};

}  // namespace comply::ur
