// comply.Client's recording (see py_client_recording.hpp).

#include "py_client_recording.hpp"

#include "comply/transport/cdr.hpp"

namespace comply::python {
namespace {

// Room for a burst: a client that polls after a long pause takes up to 10,000 diagnostics at once.
constexpr std::size_t kLaneBytes = std::size_t{16} << 20;

record::RecorderOptions recorderOptions(const std::filesystem::path& path) {
  record::RecorderOptions options;
  options.path = path.string();  // its folder must exist, as for the hosts' --record
  // The client talks to a live host: a full lane drops (and counts) rather than hold up the
  // commands the caller sends.
  options.when_full = record::WhenFull::kDrop;
  return options;
}

}  // namespace

ClientRecording::ClientRecording(const std::filesystem::path& path, const std::string& name,
                                 int domain, const std::string& network)
    : recorder_(recorderOptions(path)), lane_(recorder_.addLane("client", kLaneBytes)) {
  const std::string prefix = "/" + name + "/";
  senders_ = host::SenderChannels(recorder_, prefix);
  state_channel_ =
      host::addMessageChannel<transport::ControllerStateMessage>(recorder_, prefix + "state");
  diagnostics_channel_ =
      host::addMessageChannel<transport::DiagnosticsMessage>(recorder_, prefix + "diagnostics");
  recorder_.addMetadata("comply_client",
                        {{"host", name}, {"domain", std::to_string(domain)}, {"network", network}});
  recorder_.start();
}

template <typename Message>
void ClientRecording::push(std::uint16_t channel, const Message& message, transport::Stamp time) {
  if (!open_) {
    return;
  }
  transport::encodeCdr(message, bytes_);
  lane_.push(channel, time.nanoseconds(), bytes_.data(), bytes_.size());
}

template <typename Message>
void ClientRecording::sent(const Message& message) {
  push(senders_.of<Message>(), message, message.header.stamp);
}

template void ClientRecording::sent(const transport::CartesianCommandMessage&);
template void ClientRecording::sent(const transport::JointCommandMessage&);
template void ClientRecording::sent(const transport::CartesianChunkMessage&);
template void ClientRecording::sent(const transport::JointChunkMessage&);
template void ClientRecording::sent(const transport::RequestMessage&);

void ClientRecording::seen(const transport::ControllerStateMessage& message,
                           transport::Stamp taken) {
  push(state_channel_, message, taken);
}

void ClientRecording::seen(const transport::DiagnosticsMessage& message, transport::Stamp taken) {
  push(diagnostics_channel_, message, taken);
}

void ClientRecording::finish() {
  recorder_.stop();
}

}  // namespace comply::python
