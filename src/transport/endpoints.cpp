// Topics, QoS and the typed writers and readers over the CycloneDDS C API.

#include "comply/transport/endpoints.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <iterator>
#include <span>
#include <thread>

#include "wire.hpp"

namespace comply::transport {
namespace {

std::string_view suffixOf(Topic topic) {
#define COMPLY_TOPIC_SUFFIX(topic, Message, suffix) \
  case Topic::topic:                                \
    return suffix;
  switch (topic) { COMPLY_TOPICS(COMPLY_TOPIC_SUFFIX) }
#undef COMPLY_TOPIC_SUFFIX
  return "unknown";
}

const dds_topic_descriptor_t* descriptorOf(Topic topic) {
#define COMPLY_TOPIC_DESCRIPTOR(topic, Message, suffix) \
  case Topic::topic:                                    \
    return wire::Wire<Message>::descriptor();
  switch (topic) { COMPLY_TOPICS(COMPLY_TOPIC_DESCRIPTOR) }
#undef COMPLY_TOPIC_DESCRIPTOR
  return nullptr;
}

dds_duration_t durationOf(double seconds) {
  return static_cast<dds_duration_t>(seconds * 1e9);
}

/// ROS 2's profiles (rmw_qos_profile_default, rmw_qos_profile_sensor_data), in XCDR1 as ROS 2
/// writes.
dds_qos_t* qosFor(Topic topic, int depth) {
  QosProfile profile = qosOf(topic);
  if (depth > 0) {
    profile.depth = depth;
  }
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos,
                       profile.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       durationOf(0.1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  if (depth == kKeepAll) {
    dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
    dds_qset_resource_limits(qos, kKeepAllSamples, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  } else {
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, profile.depth);
  }
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

void check(dds_return_t code, const std::string& what) {
  if (code < 0) {
    throw TransportError("DDS: " + what + ": " + dds_strretcode(code));
  }
}

}  // namespace

std::string topicName(std::string_view host_name, Topic topic) {
  return "rt/" + std::string(host_name) + "/" + std::string(suffixOf(topic));
}

QosProfile qosOf(Topic topic) {
  switch (topic) {
    case Topic::kState:
      return {false, 5};
    case Topic::kDiagnostics:
      return {true, 100};
    default:
      return {true, 10};
  }
}

Endpoint::Endpoint(Participant& participant, std::string_view host_name, Topic topic, bool writer,
                   int depth)
    : writer_(writer) {
  const std::string name = topicName(host_name, topic);
  topic_ =
      dds_create_topic(participant.handle(), descriptorOf(topic), name.c_str(), nullptr, nullptr);
  check(topic_, "cannot create topic " + name);
  dds_qos_t* qos = qosFor(topic, depth);
  entity_ = writer ? dds_create_writer(participant.handle(), topic_, qos, nullptr)
                   : dds_create_reader(participant.handle(), topic_, qos, nullptr);
  dds_delete_qos(qos);
  check(entity_, std::string("cannot create a ") + (writer ? "writer" : "reader") + " on " + name);
}

Endpoint::~Endpoint() {
  dds_delete(entity_);
}

std::size_t Endpoint::matched() const {
  if (writer_) {
    dds_publication_matched_status_t status{};
    check(dds_get_publication_matched_status(entity_, &status), "matched status");
    return status.current_count;
  }
  dds_subscription_matched_status_t status{};
  check(dds_get_subscription_matched_status(entity_, &status), "matched status");
  return status.current_count;
}

bool Endpoint::waitForMatch(std::size_t count, double timeout_s) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (matched() < count) {
    if (std::chrono::steady_clock::now() >= deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

std::uint64_t Endpoint::instanceHandle() const {
  dds_instance_handle_t handle = 0;
  check(dds_get_instance_handle(entity_, &handle), "instance handle");
  return handle;
}

template <typename Message>
bool Writer<Message>::write(const Message& message) {
  return wire::Wire<Message>::write(entity_, message) >= 0;
}

template <typename Message>
bool Writer<Message>::flush(double timeout_s) {
  return dds_wait_for_acks(entity_, durationOf(timeout_s)) >= 0;
}

template <typename Message>
Reader<Message>::Reader(Participant& participant, std::string_view host_name, int depth)
    : Endpoint(participant, host_name, TopicOf<Message>::kTopic, false, depth), writers_(entity_) {
  waitset_ = dds_create_waitset(participant.handle());
  check(waitset_, "waitset");
  condition_ = dds_create_readcondition(entity_, DDS_ANY_STATE);
  check(condition_, "read condition");
  check(dds_waitset_attach(waitset_, condition_, 0), "waitset attach");
}

template <typename Message>
Reader<Message>::~Reader() {
  dds_delete(waitset_);
  dds_delete(condition_);
}

template <typename Message>
std::size_t Reader<Message>::take(std::vector<Sample<Message>>& out,
                                  std::vector<std::uint64_t>* departed, std::size_t max) {
  constexpr std::size_t kBatch = 64;
  void* samples[kBatch] = {};
  dds_sample_info_t infos[kBatch];
  std::size_t taken = 0;
  while (taken < max) {
    const std::size_t want = std::min(kBatch, max - taken);
    std::fill(std::begin(samples), std::end(samples), nullptr);  // null: DDS lends the samples
    const dds_return_t count = dds_take(entity_, samples, infos, want, static_cast<uint32_t>(want));
    if (count <= 0) {
      break;
    }
    for (dds_return_t i = 0; i < count; ++i) {
      if (!infos[i].valid_data) {
        continue;  // an instance state change (a writer went away), no message
      }
      Sample<Message>& sample = out.emplace_back();
      sample.publisher = infos[i].publication_handle;
      const WriterSender sender = writers_.senderOf(infos[i].publication_handle);
      sample.participant = sender.participant;
      sample.sender = sender.gid;
      wire::Wire<Message>::read(samples[i], sample);
      ++taken;
    }
    dds_return_loan(entity_, samples, count);
    if (static_cast<std::size_t>(count) < want) {
      break;
    }
  }
  if (departed != nullptr) {
    writers_.noteDepartures(*departed);
  }
  return taken;
}

template <typename Message>
bool Reader<Message>::wait(double timeout_s) {
  return dds_waitset_wait(waitset_, nullptr, 0, durationOf(timeout_s)) > 0;
}

WaitSet::WaitSet(Participant& participant) {
  waitset_ = dds_create_waitset(participant.handle());
  check(waitset_, "waitset");
  guard_ = dds_create_guardcondition(participant.handle());
  check(guard_, "guard condition");
  check(dds_waitset_attach(waitset_, guard_, 0), "waitset attach");
}

WaitSet::~WaitSet() {
  dds_delete(waitset_);
  for (const std::int32_t condition : conditions_) {
    dds_delete(condition);
  }
  dds_delete(guard_);
}

void WaitSet::attach(const Endpoint& reader) {
  const dds_entity_t condition = dds_create_readcondition(reader.handle(), DDS_ANY_STATE);
  check(condition, "read condition");
  conditions_.push_back(condition);
  check(dds_waitset_attach(waitset_, condition, 0), "waitset attach");
}

bool WaitSet::wait(double timeout_s) {
  const bool woken = dds_waitset_wait(waitset_, nullptr, 0, durationOf(timeout_s)) > 0;
  dds_set_guardcondition(guard_, false);
  return woken;
}

void WaitSet::trigger() {
  dds_set_guardcondition(guard_, true);
}

template class Writer<CartesianCommandMessage>;
template class Writer<JointCommandMessage>;
template class Writer<CartesianChunkMessage>;
template class Writer<JointChunkMessage>;
template class Writer<RequestMessage>;
template class Writer<ControllerStateMessage>;
template class Writer<DiagnosticsMessage>;
template class Writer<CommittedRequestMessage>;
template class Writer<CommittedMessage>;
template class Reader<CartesianCommandMessage>;
template class Reader<JointCommandMessage>;
template class Reader<CartesianChunkMessage>;
template class Reader<JointChunkMessage>;
template class Reader<RequestMessage>;
template class Reader<ControllerStateMessage>;
template class Reader<DiagnosticsMessage>;
template class Reader<CommittedRequestMessage>;
template class Reader<CommittedMessage>;

}  // namespace comply::transport
