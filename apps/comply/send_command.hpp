#pragma once
// `comply send` and `comply echo`: one command (or a stream of them) to a host, and the host's
// state and diagnostics as text or JSON lines.

#include <iosfwd>
#include <string>

#include "comply/transport/participant.hpp"

namespace comply::app {

struct ClientOptions {
  int domain_id = 0;
  std::string network = "loopback";
  std::string name = "comply";
  double timeout_s = 5.0;  ///< to find the host, and for each outcome
  std::string security;    ///< DDS Security's enclave folder (transport/participant.hpp)
};

/// The DDS participant a client (send, echo) uses.
transport::ParticipantOptions participantOptions(const ClientOptions& client);

struct SendOptions {
  ClientOptions client;
  std::string json;      ///< one command as a JSON object
  std::string file;      ///< one command (JSON/YAML object) or a stream (list / JSON lines)
  std::string kind;      ///< cartesian | joint; default: what the host takes
  double rate_hz = 0.0;  ///< a stream: commands per second (default 100)
  std::string request;   ///< activate | deactivate | reset instead of a command
  bool no_wait = false;  ///< do not wait for the outcomes
};

struct EchoOptions {
  ClientOptions client;
  /// state | diagnostics | both (state and diagnostics) | committed (every client's answers)
  std::string topic = "state";
  bool json = false;
  int count = 0;  ///< messages to print; 0: until interrupted
};

int sendCommand(const SendOptions& options, std::ostream& out, std::ostream& err);
int echoCommand(const EchoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
