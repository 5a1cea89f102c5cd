// The control thread's bookkeeping for `comply run` (see live_observer.hpp).

#include "live_observer.hpp"

#include <ctime>

#include "comply/core/clock.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/schema/schema.hpp"

namespace comply::host {
namespace {

using hardware::monotonicSeconds;

void count(std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins,
           double seconds) noexcept {
  const double bin = seconds / LoopCounters::kBinSeconds;
  const std::size_t index =
      bin <= 0.0 ? 0 : std::min(static_cast<std::size_t>(bin), LoopCounters::kBins - 1);
  bins[index].fetch_add(1, std::memory_order_relaxed);
}

template <typename Command>
using BusOfCommand = pipeline::BusOf<Command>;

}  // namespace

double histogramQuantile(const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins,
                         double p) {
  std::uint64_t total = 0;
  for (const auto& bin : bins) {
    total += bin.load(std::memory_order_relaxed);
  }
  if (total == 0) {
    return 0.0;
  }
  const double wanted = p * static_cast<double>(total);
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    seen += bins[i].load(std::memory_order_relaxed);
    if (static_cast<double>(seen) >= wanted) {
      return static_cast<double>(i + 1) * LoopCounters::kBinSeconds;
    }
  }
  return static_cast<double>(bins.size()) * LoopCounters::kBinSeconds;
}

template <typename Command>
LiveObserver<Command>::LiveObserver(pipeline::Wrapper<Command>& wrapper,
                                    pipeline::CommandGate& gate, hardware::HardwareInterface& robot,
                                    double wall_origin_s)
    : wrapper_(wrapper),
      robot_(robot),
      wall_origin_s_(wall_origin_s),
      gate_(gate),
      inactive_pose_(wrapper.controller().model()) {
  const int dof = wrapper.dof();
  sample_.joints = JointState::zero(dof);
  sample_.torque.setZero(dof);
  sample_.reference_joint_position.setZero(dof);
  last_state_ = JointState::zero(dof);
}

template <typename Command>
void LiveObserver<Command>::beforeCycle(std::uint64_t /*index*/, double time_s) {
  count(counters_.lateness, monotonicSeconds() - wall_origin_s_ - time_s);
  const auto request = static_cast<transport::RequestType>(
      lifecycle_request_.exchange(0, std::memory_order_acq_rel));
  // Lifecycle transitions run between cycles on this thread; they are rare operator requests,
  // not part of the cycle's real-time budget.
  if (request == transport::RequestType::kActivate) {
    try {
      wrapper_.activate(last_state_);
    } catch (const std::exception& error) {
      activation_error_.write("activation failed: ", error.what(), 1);
    }
  } else if (request == transport::RequestType::kDeactivate) {
    wrapper_.deactivate();
  }
}

template <typename Command>
void LiveObserver<Command>::afterCycle(const hardware::CycleRecord& record) {
  counters_.cycles.fetch_add(1, std::memory_order_relaxed);
  if (record.overrun) {
    counters_.overruns.fetch_add(1, std::memory_order_relaxed);
  }
  count(counters_.compute, record.compute_s);
  if (record.state != nullptr) {
    last_state_ = *record.state;
  }
  if (!gate_.noteCycle(record.index, wrapper_.controller().stampInForce(), wallClockNanoseconds)) {
    counters_.applied_deferred.fetch_add(1, std::memory_order_relaxed);
  }
  fillSample(record);
}

template <typename Command>
void LiveObserver<Command>::fillSample(const hardware::CycleRecord& record) noexcept {
  StateSample& s = sample_;
  s.cycle = record.index;
  s.wall = transport::Stamp::now();
  const pipeline::Diagnostics& diagnostics = wrapper_.controller().diagnostics();
  s.state = diagnostics.state.load(std::memory_order_relaxed);
  s.passivity = diagnostics.passivity();  // atomics only: no allocation on this thread
  s.joints = last_state_;
  for (std::size_t i = 0; i < record.torque.size(); ++i) {
    s.torque[static_cast<Eigen::Index>(i)] = record.wrote ? record.torque[i] : 0.0;
  }
  const model::Data* pose = &wrapper_.controller().modelData();
  if (s.state == pipeline::WrapperState::kInactive) {
    // No cycle measures while inactive: the state must still show where the arm is.
    const std::span<const double> q(last_state_.position.data(),
                                    static_cast<std::size_t>(last_state_.position.size()));
    if (model::update(wrapper_.controller().model(), inactive_pose_, q, q,
                      model::Quantity::kJacobian) == model::UpdateStatus::kOk) {
      pose = &inactive_pose_;
    }
  }
  const model::Data& data = *pose;
  s.tcp_position = data.tip_position;
  s.tcp_orientation = data.tip_orientation;
  const int dof = wrapper_.dof();
  s.tcp_twist =
      data.jacobian.cols() == dof ? Vector6d(data.jacobian * s.joints.velocity) : Vector6d::Zero();
  // The control thread is the one that reads the hardware: the wrench is read here, in the cycle.
  if (!robot_.readWrench(s.contact_wrench)) {
    s.contact_wrench.setZero();
  }
  const auto& bus = std::get<BusOfCommand<Command>>(wrapper_.controller().activeCommand());
  s.reference_stamp_s = bus.stamp_s;
  s.reference_fields = bus.fields;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    s.reference_position = Eigen::Vector3d(bus.position[0], bus.position[1], bus.position[2]);
    s.reference_orientation = schema::fromXyzw(bus.orientation);
  } else {
    for (int i = 0; i < dof; ++i) {
      s.reference_joint_position[i] = bus.position[i];
    }
  }
  state_.publishFromSoleWriter(s);
}

template <typename Command>
void LiveObserver<Command>::requestLifecycle(transport::RequestType request) noexcept {
  lifecycle_request_.store(static_cast<std::uint8_t>(request), std::memory_order_release);
}

template <typename Command>
std::string LiveObserver<Command>::activationError() const {
  return activation_error_.read().first;
}

template <typename Command>
bool LiveObserver<Command>::takeState(StateSample& sample) {
  if (!state_.update()) {
    return false;
  }
  sample = state_.read();
  return true;
}

template class LiveObserver<CartesianCommand>;
template class LiveObserver<JointCommand>;

}  // namespace comply::host
