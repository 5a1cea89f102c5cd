#pragma once
// Typed DDS writers and readers for comply's topics, named and configured as ROS 2 names and
// configures them, so a ROS 2 node (rmw_cyclonedds) talks to a comply host as to any node. For
// a host named <name> (the ROS topic /<name>/x is the DDS topic rt/<name>/x):
//
//   ROS topic                   DDS type (module comply_msgs::msg::dds_)   QoS
//   /<name>/cartesian_command   CartesianCommand_                          R
//   /<name>/joint_command       JointCommand_                              R
//   /<name>/cartesian_chunk     CartesianChunk_                            R
//   /<name>/joint_chunk         JointChunk_                                R
//   /<name>/request             Request_                                   R
//   /<name>/state               ControllerState_                           S
//   /<name>/diagnostics         Diagnostics_                               D
//   /<name>/committed_request   CommittedRequest_                          R
//   /<name>/committed           Committed_                                 R
//
// R: ROS 2's default (reliable, volatile, keep last 10). S: the sensor-data profile (best effort,
// volatile, keep last 5). D: reliable, volatile, keep last 100, so that a reader that keeps up
// loses no command outcome. Samples are written in XCDR1 (plain CDR, little-endian), as ROS 2.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "comply/transport/matched_writers.hpp"
#include "comply/transport/messages.hpp"
#include "comply/transport/participant.hpp"

namespace comply::transport {

/// Every topic: its enumerator (in this order: the numbers travel between a host and its transport
/// process), the message it carries and its name under /<host_name>/.
// clang-format off
#define COMPLY_TOPICS(X)                                              \
  X(kCartesianCommand, CartesianCommandMessage, "cartesian_command") \
  X(kJointCommand, JointCommandMessage, "joint_command")             \
  X(kRequest, RequestMessage, "request")                             \
  X(kCartesianChunk, CartesianChunkMessage, "cartesian_chunk")       \
  X(kJointChunk, JointChunkMessage, "joint_chunk")                   \
  X(kState, ControllerStateMessage, "state")                         \
  X(kDiagnostics, DiagnosticsMessage, "diagnostics")                 \
  X(kCommittedRequest, CommittedRequestMessage, "committed_request") \
  X(kCommitted, CommittedMessage, "committed")
// clang-format on

#define COMPLY_TOPIC_ENUMERATOR(topic, Message, suffix) topic,
enum class Topic : std::uint8_t { COMPLY_TOPICS(COMPLY_TOPIC_ENUMERATOR) };
#undef COMPLY_TOPIC_ENUMERATOR

/// "rt/<host_name>/<topic>": the DDS name of the ROS topic /<host_name>/<topic>.
std::string topicName(std::string_view host_name, Topic topic);

struct QosProfile {
  bool reliable = true;
  int depth = 10;  ///< keep last
};

/// An endpoint depth that keeps every sample until it is taken or acknowledged (KEEP_ALL, at most
/// kKeepAllSamples held): a reliable writer then waits for room instead of dropping its oldest
/// unacknowledged sample, and a reliable reader that is full holds the writer back through the
/// protocol instead of discarding a burst. History is not matched between endpoints, so either
/// side stays compatible with ROS 2's keep-last peers (which may still drop on their own side).
inline constexpr int kKeepAll = -1;
inline constexpr int kKeepAllSamples = 1000;
QosProfile qosOf(Topic topic);

/// The topic each message travels on.
template <typename Message>
struct TopicOf;
#define COMPLY_TOPIC_OF(topic, Message, suffix)   \
  template <>                                     \
  struct TopicOf<Message> {                       \
    static constexpr Topic kTopic = Topic::topic; \
  };
COMPLY_TOPICS(COMPLY_TOPIC_OF)
#undef COMPLY_TOPIC_OF

/// What the entities of every message type share: the DDS handles and their matching.
class Endpoint {
 public:
  Endpoint(const Endpoint&) = delete;
  Endpoint& operator=(const Endpoint&) = delete;
  [[nodiscard]] std::int32_t handle() const noexcept { return entity_; }
  /// Remote (or local) endpoints currently matched.
  [[nodiscard]] std::size_t matched() const;
  /// Waits until at least `count` endpoints match; false on timeout.
  bool waitForMatch(std::size_t count, double timeout_s) const;
  /// This endpoint's DDS instance handle: what a reader reports as a sample's publisher.
  [[nodiscard]] std::uint64_t instanceHandle() const;

 protected:
  Endpoint(Participant& participant, std::string_view host_name, Topic topic, bool writer,
           int depth = 0);
  ~Endpoint();
  bool writer_;
  std::int32_t topic_ = 0;
  std::int32_t entity_ = 0;
};

template <typename Message>
class Writer final : public Endpoint {
 public:
  /// `depth` > 0 replaces the topic's keep-last depth for this writer; kKeepAll keeps all.
  Writer(Participant& participant, std::string_view host_name, int depth = 0)
      : Endpoint(participant, host_name, TopicOf<Message>::kTopic, true, depth) {}
  /// False when DDS refused the sample (it is then not sent).
  bool write(const Message& message);
  /// Waits until every matched reliable reader acknowledged what was written; false on timeout.
  bool flush(double timeout_s);
};

template <typename Message>
class Reader final : public Endpoint {
 public:
  /// `depth` > 0 replaces the topic's keep-last depth for this reader alone, kKeepAll keeps all
  /// (history is not matched against the writers', so either stays compatible with ROS 2 peers).
  Reader(Participant& participant, std::string_view host_name, int depth = 0);
  ~Reader();
  /// Appends up to `max` waiting samples to `out` in arrival order; how many. A writer that
  /// unmatched since the last call (deleted, or its process ended) goes to `departed`, if given.
  std::size_t take(std::vector<Sample<Message>>& out,
                   std::vector<std::uint64_t>* departed = nullptr, std::size_t max = 64);
  /// Waits until a sample waits to be taken; false on timeout.
  bool wait(double timeout_s);

 private:
  std::int32_t waitset_ = 0;
  std::int32_t condition_ = 0;
  MatchedWriters writers_;
};

/// Waits on several readers at once (the host's reader thread).
class WaitSet {
 public:
  explicit WaitSet(Participant& participant);
  ~WaitSet();
  WaitSet(const WaitSet&) = delete;
  WaitSet& operator=(const WaitSet&) = delete;
  void attach(const Endpoint& reader);
  /// Waits until one of the readers has data or trigger() was called; false on timeout.
  bool wait(double timeout_s);
  /// Any thread: wakes wait() (to shut down).
  void trigger();

 private:
  std::int32_t waitset_ = 0;
  std::int32_t guard_ = 0;
  std::vector<std::int32_t> conditions_;
};

extern template class Writer<CartesianCommandMessage>;
extern template class Writer<JointCommandMessage>;
extern template class Writer<CartesianChunkMessage>;
extern template class Writer<JointChunkMessage>;
extern template class Writer<RequestMessage>;
extern template class Writer<ControllerStateMessage>;
extern template class Writer<DiagnosticsMessage>;
extern template class Writer<CommittedRequestMessage>;
extern template class Writer<CommittedMessage>;
extern template class Reader<CartesianCommandMessage>;
extern template class Reader<JointCommandMessage>;
extern template class Reader<CartesianChunkMessage>;
extern template class Reader<JointChunkMessage>;
extern template class Reader<RequestMessage>;
extern template class Reader<ControllerStateMessage>;
extern template class Reader<DiagnosticsMessage>;
extern template class Reader<CommittedRequestMessage>;
extern template class Reader<CommittedMessage>;

}  // namespace comply::transport
