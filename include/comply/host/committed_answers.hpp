#pragma once
// A host's answers to committed requests (comply_msgs/CommittedRequest): the reference its cycles
// will write at the times asked for if no new command arrives, from the wrapper's own prediction
// (pipeline::Wrapper::predict), on a thread that takes requests (`comply run`'s reader, a ROS 2
// controller's executor). Never on the cycle's: the cycle does no work for them.

#include <cstdint>
#include <string>
#include <vector>

#include "comply/pipeline/wrapper.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

/// Why `request` cannot be answered, naming the field ("dt is 0: ..."); "" when it can.
std::string committedRequestRefusal(
    const transport::Sample<transport::CommittedRequestMessage>& sample);

template <typename Command>
class CommittedAnswers {
 public:
  /// `frame_id`: the base frame, which the answers' header names.
  CommittedAnswers(pipeline::Wrapper<Command>& wrapper, std::string frame_id)
      : wrapper_(wrapper), frame_id_(std::move(frame_id)) {}

  /// The answer to `sample` with the host's clock reading `clock_ns` [ns since the epoch] now (the
  /// wall clock, which a chunk's times are on): valid until the next call. Its times map onto the
  /// controller's clock as the intake maps a chunk's (Wrapper::submitChunk's host_time_s).
  const transport::CommittedMessage& answer(
      const transport::Sample<transport::CommittedRequestMessage>& sample, std::int64_t clock_ns);

 private:
  pipeline::Wrapper<Command>& wrapper_;
  std::string frame_id_;
  // Kept from one answer to the next: once grown, an answer allocates only in predict().
  std::vector<std::int64_t> times_ns_;
  std::vector<double> times_s_;
  std::vector<Command> predicted_;
  transport::CommittedMessage answer_;
};

extern template class CommittedAnswers<CartesianCommand>;
extern template class CommittedAnswers<JointCommand>;

}  // namespace comply::host
