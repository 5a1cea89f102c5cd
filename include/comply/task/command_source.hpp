#pragma once
// A command source: what a host asks for at the command rate. Waypoint trajectories, a stream
// along a path (PathCommand), an experiment's stream and a live policy all implement it, so a
// host (the simulator, `comply run`, a test) drives any of them the same way.
//
//   every command period:  if (auto command = source.next(t, measured)) wrapper.submit(*command);
//
// Commands are typed and carry their field mask; nothing is parsed in the loop.

#include <optional>

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"

namespace comply::task {

template <typename Command>
class CommandSource {
 public:
  virtual ~CommandSource() = default;

  /// The command to submit at controller time `t_s` [s since activation], given the pose the
  /// controller last measured; nothing when there is nothing new to send.
  virtual std::optional<Command> next(double t_s, const MeasuredPose& measured) = 0;

  /// Time [s] at which the commanded motion ends (settle times count from it); 0 when it does
  /// not move.
  [[nodiscard]] virtual double motionEndTime() const { return 0.0; }
};

using CartesianSource = CommandSource<CartesianCommand>;
using JointSource = CommandSource<JointCommand>;

}  // namespace comply::task
