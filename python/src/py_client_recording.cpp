// comply.Client's recording (see py_client_recording.hpp).

#include "py_client_recording.hpp"

#include "comply/transport/cdr.hpp"

namespace comply::python {
namespace {

// Room for a burst: a client that polls after a long pause takes up to 10,000 diagnostics at once.
constexpr std::size_t kLaneBytes = std::size_t{16} << 20;

record::RecorderOptions recorderOptions(const std::filesystem::path& path) {
  // record="runs/today/a.mcap" makes its folder, as the hosts' --record does.
  if (path.has_parent_path()) {
    std::error_code ignored;  // an uncreatable folder shows as the file's own error
    std::filesystem::create_directories(path.parent_path(), ignored);
  }
  record::RecorderOptions options;
  options.path = path.string();
  return options;
}

}  // namespace

template <typename Message>
std::uint16_t ClientRecording::addChannel(const std::string& topic) {
  const std::string_view type = transport::rosTypeName<Message>();
  const std::uint16_t schema =
      recorder_.addSchema(type, "ros2msg", transport::ros2MessageDefinition(type));
  return recorder_.addChannel(schema, topic);
}

ClientRecording::ClientRecording(const std::filesystem::path& path, const std::string& name,
                                 int domain, const std::string& network)
    : recorder_(recorderOptions(path)), lane_(recorder_.addLane("client", kLaneBytes)) {
  const std::string prefix = "/" + name + "/";
  cartesian_channel_ = addChannel<transport::CartesianCommandMessage>(prefix + "cartesian_command");
  joint_channel_ = addChannel<transport::JointCommandMessage>(prefix + "joint_command");
  cartesian_chunk_channel_ =
      addChannel<transport::CartesianChunkMessage>(prefix + "cartesian_chunk");
  joint_chunk_channel_ = addChannel<transport::JointChunkMessage>(prefix + "joint_chunk");
  request_channel_ = addChannel<transport::RequestMessage>(prefix + "request");
  state_channel_ = addChannel<transport::ControllerStateMessage>(prefix + "state");
  diagnostics_channel_ = addChannel<transport::DiagnosticsMessage>(prefix + "diagnostics");
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

void ClientRecording::sent(const transport::CartesianCommandMessage& message) {
  push(cartesian_channel_, message, message.header.stamp);
}

void ClientRecording::sent(const transport::JointCommandMessage& message) {
  push(joint_channel_, message, message.header.stamp);
}

void ClientRecording::sent(const transport::CartesianChunkMessage& message) {
  push(cartesian_chunk_channel_, message, message.header.stamp);
}

void ClientRecording::sent(const transport::JointChunkMessage& message) {
  push(joint_chunk_channel_, message, message.header.stamp);
}

void ClientRecording::sent(const transport::RequestMessage& message) {
  push(request_channel_, message, message.header.stamp);
}

void ClientRecording::seen(const transport::ControllerStateMessage& message,
                           transport::Stamp taken) {
  push(state_channel_, message, taken);
}

void ClientRecording::seen(const transport::DiagnosticsMessage& message, transport::Stamp taken) {
  push(diagnostics_channel_, message, taken);
}

void ClientRecording::stop() {
  open_ = false;
  recorder_.stop();
}

}  // namespace comply::python
