#pragma once
// A command source: what a host asks for at the command rate. Waypoint trajectories, a stream
// along a path (PathCommand), an experiment's stream and a live policy all implement it, so a
// host (the simulator, `comply run`, a test) drives any of them the same way.
//
//   every command period:  if (auto command = source.next(t, measured)) wrapper.submit(*command);
//
// Commands are typed and carry their field mask; nothing is parsed in the loop.

#include <functional>
#include <memory>
#include <optional>
#include <utility>

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

/// A source from a callable, for streams that are easiest written as a lambda.
template <typename Command>
class FunctionSource final : public CommandSource<Command> {
 public:
  using Function = std::function<std::optional<Command>(double, const MeasuredPose&)>;
  explicit FunctionSource(Function function, double motion_end_s = 0.0)
      : function_(std::move(function)), motion_end_s_(motion_end_s) {}
  std::optional<Command> next(double t_s, const MeasuredPose& measured) override {
    return function_(t_s, measured);
  }
  [[nodiscard]] double motionEndTime() const override { return motion_end_s_; }

 private:
  Function function_;
  double motion_end_s_;
};

/// Asks `inner` only every `period_s` (from t = 0): a stream at a command rate below the control
/// rate, as a policy or a teleoperator sends.
template <typename Command>
class PacedSource final : public CommandSource<Command> {
 public:
  PacedSource(CommandSource<Command>& inner, double period_s, double control_period_s)
      : inner_(inner), period_s_(period_s), slack_s_(0.5 * control_period_s) {}
  std::optional<Command> next(double t_s, const MeasuredPose& measured) override {
    if (t_s < next_s_ - slack_s_) {
      return std::nullopt;
    }
    next_s_ += period_s_;
    return inner_.next(t_s, measured);
  }
  [[nodiscard]] double motionEndTime() const override { return inner_.motionEndTime(); }

 private:
  CommandSource<Command>& inner_;
  double period_s_;
  double slack_s_;
  double next_s_ = 0.0;
};

using CartesianSource = CommandSource<CartesianCommand>;
using JointSource = CommandSource<JointCommand>;

}  // namespace comply::task
