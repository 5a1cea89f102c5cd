// The participant, its loopback configuration and the domains of this process.

#include "comply/transport/participant.hpp"

#include <dds/dds.h>
#include <dlfcn.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "comply/core/realtime_scheduling.hpp"

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

/// `options` with no receive priority where this process may not have it: CycloneDDS gives up
/// on a domain whose receive threads it cannot start as configured.
ParticipantOptions withGrantedPriority(ParticipantOptions options) {
  if (const std::string refusal = realtimeRefusal(options.receive_priority); !refusal.empty()) {
    std::fprintf(stderr,
                 "comply: DDS: warning: no real-time scheduling for the receive threads (%s): "
                 "they run at normal priority; to grant it, %s\n",
                 refusal.c_str(), kRealtimeGrantAdvice);
    options.receive_priority = 0;
  }
  return options;
}

void acquireDomain(const ParticipantOptions& options) {
  const std::lock_guard<std::mutex> lock(domains_mutex);
  DomainUse& use = domains()[options.domain_id];
  if (use.users++ > 0) {
    return;
  }
  const std::string config = cycloneConfig(withGrantedPriority(options));
  if (config.empty()) {
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

/// A security plug-in of CycloneDDS: Debian installs them beside libddsc, in libddsc0debian/;
/// elsewhere CycloneDDS finds them by name on the library path.
std::string securityLibrary(const std::string& name) {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&dds_create_participant), &info) != 0 &&
      info.dli_fname != nullptr) {
    const std::filesystem::path folder = std::filesystem::path(info.dli_fname).parent_path();
    for (const auto& candidate :
         {folder / "libddsc0debian" / ("lib" + name + ".so"), folder / ("lib" + name + ".so")}) {
      std::error_code error;
      if (std::filesystem::is_regular_file(candidate, error)) {
        return candidate.string();
      }
    }
  }
  return name;
}

/// The participant QoS that turns DDS Security on with the enclave `folder`'s files. Throws
/// TransportError naming a file that is not there.
dds_qos_t* securityQos(const std::filesystem::path& folder) {
  constexpr std::array<const char*, 6> kFiles = {
      "identity_ca.cert.pem",    "cert.pem",       "key.pem",
      "permissions_ca.cert.pem", "governance.p7s", "permissions.p7s"};
  for (const char* file : kFiles) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(folder / file, error)) {
      throw TransportError("DDS Security: " + (folder / file).string() +
                           " is not there: --security takes an enclave folder of a keystore "
                           "(scripts/create-keystore.sh KEYSTORE /comply/host makes "
                           "KEYSTORE/enclaves/comply/host)");
    }
  }
  const auto uri = [&folder](const char* file) {
    return "file:" + std::filesystem::absolute(folder / file).string();
  };
  dds_qos_t* qos = dds_create_qos();
  const std::array<std::pair<const char*, std::string>, 15> properties = {{
      {"dds.sec.auth.library.path", securityLibrary("dds_security_auth")},
      {"dds.sec.auth.library.init", "init_authentication"},
      {"dds.sec.auth.library.finalize", "finalize_authentication"},
      {"dds.sec.crypto.library.path", securityLibrary("dds_security_crypto")},
      {"dds.sec.crypto.library.init", "init_crypto"},
      {"dds.sec.crypto.library.finalize", "finalize_crypto"},
      {"dds.sec.access.library.path", securityLibrary("dds_security_ac")},
      {"dds.sec.access.library.init", "init_access_control"},
      {"dds.sec.access.library.finalize", "finalize_access_control"},
      {"dds.sec.auth.identity_ca", uri("identity_ca.cert.pem")},
      {"dds.sec.auth.identity_certificate", uri("cert.pem")},
      {"dds.sec.auth.private_key", uri("key.pem")},
      {"dds.sec.access.permissions_ca", uri("permissions_ca.cert.pem")},
      {"dds.sec.access.governance", uri("governance.p7s")},
      {"dds.sec.access.permissions", uri("permissions.p7s")},
  }};
  for (const auto& [name, value] : properties) {
    dds_qset_prop(qos, name, value.c_str());
  }
  return qos;
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
  dds_qos_t* qos = options.security.empty() ? nullptr : securityQos(options.security);
  acquireDomain(options);
  participant_ =
      dds_create_participant(static_cast<dds_domainid_t>(options.domain_id), qos, nullptr);
  if (qos != nullptr) {
    dds_delete_qos(qos);
  }
  if (participant_ < 0) {
    releaseDomain(options.domain_id);
    throw TransportError(std::string("DDS: cannot create a participant on domain ") +
                         std::to_string(options.domain_id) + ": " + dds_strretcode(participant_) +
                         (options.security.empty()
                              ? ""
                              : " (DDS Security with " + options.security.string() +
                                    ": CycloneDDS's log above says which file it refused)"));
  }
}

Gid Participant::gid() const {
  dds_guid_t guid{};
  Gid gid{};
  if (dds_get_guid(participant_, &guid) == DDS_RETCODE_OK) {
    std::memcpy(gid.data(), guid.v, gid.size());
  }
  return gid;
}

Participant::~Participant() {
  dds_delete(participant_);
  releaseDomain(options_.domain_id);
}

}  // namespace comply::transport
