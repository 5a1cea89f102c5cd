// The live host's DDS transport (see dds_host_transport.hpp).

#include "comply/transport/dds_host_transport.hpp"

#include <dds/dds.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "comply/transport/endpoints.hpp"
#include "comply/transport/participant.hpp"
#include "malformed_log.hpp"

namespace comply::transport {
namespace {

class DdsHostTransport final : public HostTransport {
 public:
  // Every command kept until the host takes it: a burst that arrives while the reader thread is
  // descheduled, or faster than it validates, waits here (and holds a reliable writer back)
  // instead of being dropped unaccounted.
  static constexpr int kCommandDepth = kKeepAll;

  explicit DdsHostTransport(const HostTransportOptions& options)
      : options_(options),
        participant_({options.domain_id,
                      options.network == "all" ? Network::kAll : Network::kLoopback,
                      options.receive_priority, options.security}),
        cartesian_(participant_, options.name, kCommandDepth),
        joint_(participant_, options.name, kCommandDepth),
        cartesian_chunks_(participant_, options.name, kCommandDepth),
        joint_chunks_(participant_, options.name, kCommandDepth),
        request_(participant_, options.name),
        state_(participant_, options.name),
        diagnostics_(participant_, options.name),
        waitset_(participant_) {
    openCommitted();
    for (const Endpoint* reader : readers()) {
      waitset_.attach(*reader);
    }
  }

  ~DdsHostTransport() override {
    // The listeners first: no callback may run into a transport being taken apart.
    for (const Endpoint* reader : readers()) {
      dds_set_listener(reader->handle(), nullptr);
    }
  }
  DdsHostTransport(const DdsHostTransport&) = delete;
  DdsHostTransport& operator=(const DdsHostTransport&) = delete;

  bool notifyOnInput(const std::function<void()>& on_input) override {
    on_input_ = on_input;
    dds_listener_t* listener = dds_create_listener(this);
    dds_lset_data_available(listener, [](dds_entity_t /*reader*/, void* self) {
      static_cast<DdsHostTransport*>(self)->on_input_();
    });
    bool set = true;
    for (const Endpoint* reader : readers()) {
      set = set && dds_set_listener(reader->handle(), listener) == DDS_RETCODE_OK;
    }
    dds_delete_listener(listener);
    if (!set) {
      // All or none: a caller told "no" goes on with receive() alone, which must not race a
      // listener left on some of the readers.
      for (const Endpoint* reader : readers()) {
        dds_set_listener(reader->handle(), nullptr);
      }
    }
    return set;
  }

  void receive(Inbox& inbox, double timeout_s) override {
    // Malformed samples never wake the wait set: a count owed is printed from here.
    malformed_log_.tick();
    waitset_.wait(timeout_s);
    cartesian_.take(inbox.cartesian, &inbox.departed);
    joint_.take(inbox.joint, &inbox.departed);
    cartesian_chunks_.take(inbox.cartesian_chunks, &inbox.departed);
    joint_chunks_.take(inbox.joint_chunks, &inbox.departed);
    request_.take(inbox.requests);
    if (committed_request_) {
      committed_request_->take(inbox.committed_requests);
    }
  }
  void wake() override { waitset_.trigger(); }
  void publish(const ControllerStateMessage& state) override { state_.write(state); }
  void publish(const DiagnosticsMessage& diagnostics) override { diagnostics_.write(diagnostics); }
  void publish(const CommittedMessage& answer) override {
    if (committed_) {
      committed_->write(answer);
    }
  }
  bool flush(double timeout_s) override { return diagnostics_.flush(timeout_s); }
  [[nodiscard]] std::string describe() const override {
    return "topics rt/" + options_.name + "/* on domain " + std::to_string(options_.domain_id) +
           " (" + options_.network +
           (options_.security.empty() ? "" : ", DDS Security as " + options_.security.string()) +
           ")" + committed_refused_;
  }
  [[nodiscard]] std::uint64_t malformedSamples() const override { return malformed_log_.total(); }

 private:
  [[nodiscard]] std::vector<const Endpoint*> readers() const {
    std::vector<const Endpoint*> all{&cartesian_, &joint_, &cartesian_chunks_, &joint_chunks_,
                                     &request_};
    if (committed_request_) {
      all.push_back(committed_request_.get());
    }
    return all;
  }

  /// The committed topics. Under DDS Security a keystore's permissions made before they existed
  /// refuse them: the host then runs on without answering committed requests, and says why.
  void openCommitted() {
    try {
      committed_request_ =
          std::make_unique<Reader<CommittedRequestMessage>>(participant_, options_.name);
      committed_ = std::make_unique<Writer<CommittedMessage>>(participant_, options_.name);
    } catch (const TransportError& error) {
      if (options_.security.empty()) {
        throw;
      }
      committed_request_.reset();
      committed_.reset();
      committed_refused_ = "; committed requests not answered (" + std::string(error.what()) +
                           "): the enclave's permissions predate the committed topics, make it "
                           "again with scripts/create-keystore.sh";
    }
  }

  // First: in place before the participant sees a packet, and gone after it.
  MalformedSampleLog malformed_log_;
  HostTransportOptions options_;
  Participant participant_;
  Reader<CartesianCommandMessage> cartesian_;
  Reader<JointCommandMessage> joint_;
  Reader<CartesianChunkMessage> cartesian_chunks_;
  Reader<JointChunkMessage> joint_chunks_;
  Reader<RequestMessage> request_;
  Writer<ControllerStateMessage> state_;
  Writer<DiagnosticsMessage> diagnostics_;
  std::unique_ptr<Reader<CommittedRequestMessage>> committed_request_;
  std::unique_ptr<Writer<CommittedMessage>> committed_;
  std::string committed_refused_;  ///< why there are none ("" when there are)
  WaitSet waitset_;
  std::function<void()> on_input_;
};

}  // namespace

std::unique_ptr<HostTransport> makeDdsHostTransport(const HostTransportOptions& options) {
  if (options.network != "loopback" && options.network != "all") {
    throw TransportError("network must be loopback or all, not '" + options.network + "'");
  }
  return std::make_unique<DdsHostTransport>(options);
}

}  // namespace comply::transport
