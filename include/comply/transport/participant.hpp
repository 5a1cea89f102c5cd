#pragma once
// A DDS domain participant for comply's topics (CycloneDDS). Safe by default: bound to the
// loopback interface with multicast off, so nothing leaves the machine unless the network is
// opened on purpose (`--network all`). Discovery then runs over unicast to 127.0.0.1, one port
// per participant index, so several hosts and clients on one machine find each other.
//
//   transport::Participant participant({.domain_id = 7});
//   transport::Writer<transport::CartesianCommandMessage> writer(participant, "comply");

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "comply/transport/host_transport.hpp"

namespace comply::transport {

enum class Network : std::uint8_t {
  kLoopback,  ///< sends and discovers on 127.0.0.1 only, no multicast (the default; the sockets
              ///< still bind to every address: docs/live-control.md)
  kAll,       ///< CycloneDDS's defaults: the machine's interfaces, multicast discovery
};

struct ParticipantOptions {
  int domain_id = 0;  ///< DDS domain, 0..232 (ROS_DOMAIN_ID)
  Network network = Network::kLoopback;
  /// > 0: CycloneDDS's receive threads (which deliver samples to readers) run SCHED_FIFO at this
  /// priority, so a real-time host hears commands without waiting for the scheduler.
  int receive_priority = 0;
  /// DDS Security: an enclave folder of a keystore laid out as ROS 2's SROS2 lays it out
  /// (cert.pem, key.pem, identity_ca.cert.pem, permissions_ca.cert.pem, governance.p7s,
  /// permissions.p7s; scripts/create-keystore.sh makes one). The participant then authenticates,
  /// and talks only to participants its governance and permissions admit. Empty: off.
  std::filesystem::path security{};
};

/// The CycloneDDS configuration (XML) for `options`; empty for Network::kAll.
std::string cycloneConfig(const ParticipantOptions& options);

class Participant {
 public:
  /// Throws TransportError when the domain id is out of range or DDS refuses. Participants of one
  /// process share the domain's configuration: the first one on a domain sets it.
  explicit Participant(const ParticipantOptions& options = {});
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  [[nodiscard]] std::int32_t handle() const noexcept { return participant_; }
  [[nodiscard]] const ParticipantOptions& options() const noexcept { return options_; }
  /// Its DDS GUID: how a host's CommandOutcome names this process as a command's sender.
  [[nodiscard]] Gid gid() const;

 private:
  ParticipantOptions options_;
  std::int32_t participant_ = 0;
};

}  // namespace comply::transport
