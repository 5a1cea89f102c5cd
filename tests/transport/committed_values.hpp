#pragma once
// A committed request and answers of both kinds with every field away from its default, for the
// tests of their wire forms (CDR, DDS, the transport process's frames, the in-process bus).

#include <cmath>
#include <cstdint>
#include <limits>

#include "comply/transport/messages.hpp"

namespace comply::transport::testing {

inline CommittedRequestMessage someCommittedRequest() {
  CommittedRequestMessage request;
  request.header = {{1700000000, 123456789}, "policy"};
  request.observation = {1700000000, 100000000};
  request.dt_s = 1.0 / 30.0;
  request.count = 16;
  return request;
}

/// An answer of `count` entries of the Cartesian controller's kind, the last one unknown (NaN),
/// 50 ms apart, each with its own pose and gains.
inline CommittedMessage someCartesianAnswer(int count) {
  CommittedMessage answer;
  answer.header = {{1700000001, 5}, "fr3_link0"};
  answer.request_stamp = {1700000000, 123456789};
  answer.sender = {0x01, 0x10, 0xaa, 0x55, 1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 1, 0xc1};
  answer.command_kind = WireCommandKind::kCartesian;
  answer.answered = true;
  answer.known = false;
  answer.message = "";
  for (int k = 0; k < count; ++k) {
    CartesianCommandMessage entry;
    entry.header.stamp = Stamp::fromNanoseconds(1'700'000'000'100'000'000 + k * 50'000'000LL);
    entry.command = CartesianCommand::zero(7);
    entry.command.stamp_s = entry.header.stamp.seconds();
    entry.command.fields = CommandField::kPosition | CommandField::kStiffness;
    entry.command.position = Eigen::Vector3d(0.4, -0.1 + 0.005 * k, 0.5);
    entry.command.orientation = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
    entry.command.stiffness_translational.diagonal() << 800.0 + k, 900.0, 1000.0;
    entry.command.nullspace_position.setLinSpaced(7, 0.1 * k, 0.7);
    answer.cartesian.push_back(entry);
  }
  if (count > 0) {
    answer.cartesian.back().command.position.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return answer;
}

/// A joint controller's answer of `count` entries, and a refusal has none.
inline CommittedMessage someJointAnswer(int count) {
  CommittedMessage answer;
  answer.header = {{1700000002, 7}, "base"};
  answer.request_stamp = {1700000000, 9};
  answer.command_kind = WireCommandKind::kJoint;
  answer.answered = count > 0;
  answer.known = count > 0;
  answer.message = count > 0 ? "" : "dt is 0: the step between the times [s] is finite and > 0";
  for (int k = 0; k < count; ++k) {
    JointCommandMessage entry;
    entry.header.stamp = {1700000003, static_cast<std::uint32_t>(1000 * k)};
    entry.command = JointCommand::zero(3);
    entry.command.stamp_s = entry.header.stamp.seconds();
    entry.command.position << 0.1 * k, -0.2, 0.3;
    entry.command.stiffness << 100.0, 200.0 + k, 300.0;
    entry.command.velocity.resize(0);
    answer.joint.push_back(entry);
  }
  return answer;
}

}  // namespace comply::transport::testing
