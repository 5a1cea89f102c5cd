// The participant, its loopback configuration and the domains of this process.

#include "comply/transport/participant.hpp"

#include <dds/dds.h>

#include <map>
#include <mutex>

namespace comply::transport {
namespace {

// A configured domain lives as long as a participant of this process uses it: CycloneDDS keeps
// an explicitly created domain until it is deleted, and deleting it deletes its participants.
struct DomainUse {
  dds_entity_t domain = 0;
  int users = 0;
};
std::mutex domains_mutex;
std::map<int, DomainUse>& domains() {
  static std::map<int, DomainUse> table;
  return table;
}

void acquireDomain(const ParticipantOptions& options) {
  const std::lock_guard<std::mutex> lock(domains_mutex);
  DomainUse& use = domains()[options.domain_id];
  const std::string config = cycloneConfig(options);
  if (use.users++ > 0 || config.empty()) {
    return;
  }
  use.domain = dds_create_domain(static_cast<dds_domainid_t>(options.domain_id), config.c_str());
  if (use.domain < 0) {
    --use.users;
    throw TransportError(std::string("DDS: cannot create domain ") +
                         std::to_string(options.domain_id) + ": " + dds_strretcode(use.domain));
  }
}

void releaseDomain(int domain_id) {
  const std::lock_guard<std::mutex> lock(domains_mutex);
  DomainUse& use = domains()[domain_id];
  if (--use.users == 0 && use.domain > 0) {
    dds_delete(use.domain);
    use.domain = 0;
  }
}

}  // namespace

std::string cycloneConfig(const ParticipantOptions& options) {
  std::string threads;
  if (options.receive_priority > 0) {
    threads = "<Threads>";
    for (const char* name : {"recv", "dq.user"}) {
      threads += std::string("<Thread Name=\"") + name +
                 "\"><Scheduling><Class>realtime</Class><Priority>" +
                 std::to_string(options.receive_priority) + "</Priority></Scheduling></Thread>";
    }
    threads += "</Threads>";
  }
  if (options.network == Network::kAll) {
    return threads.empty() ? ""
                           : "<CycloneDDS><Domain Id=\"any\">" + threads + "</Domain></CycloneDDS>";
  }
  // Unicast discovery on 127.0.0.1 reaches participant indices 0..MaxAutoParticipantIndex, one
  // port each: room for the host, its clients and a few tools per domain on one machine.
  return "<CycloneDDS><Domain Id=\"any\"><General>"
         "<Interfaces><NetworkInterface address=\"127.0.0.1\" multicast=\"false\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
         "<MaxAutoParticipantIndex>31</MaxAutoParticipantIndex>"
         "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>" +
         threads + "</Domain></CycloneDDS>";
}

Participant::Participant(const ParticipantOptions& options) : options_(options) {
  if (options.domain_id < 0 || options.domain_id > 232) {
    throw TransportError("DDS domain id " + std::to_string(options.domain_id) +
                         " out of range 0..232");
  }
  acquireDomain(options);
  participant_ =
      dds_create_participant(static_cast<dds_domainid_t>(options.domain_id), nullptr, nullptr);
  if (participant_ < 0) {
    releaseDomain(options.domain_id);
    throw TransportError(std::string("DDS: cannot create a participant on domain ") +
                         std::to_string(options.domain_id) + ": " + dds_strretcode(participant_));
  }
}

Participant::~Participant() {
  dds_delete(participant_);
  releaseDomain(options_.domain_id);
}

}  // namespace comply::transport
