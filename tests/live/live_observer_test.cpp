// The live host's control-thread bookkeeping for operator requests (live_observer.hpp): an
// activation or deactivation is settled once the control thread carried it out, in the order sent,
// an activation that failed is refused with why, and a reset is settled with what the cycle
// decided.

#include "live_observer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "comply/host/controller_setup.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::host {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

class LiveObserverRequests : public ::testing::Test {
 protected:
  LiveObserverRequests()
      : wrapper(pipeline::resolveController(simControllerConfig(
            "fr3", "", COMPLY_SOURCE_DIR "/config/sim/cartesian_impedance.yaml"))),
        gate({.kind = pipeline::CommandKind::kCartesian, .publisher_timeout_s = 600.0}),
        observer(wrapper, gate) {}

  std::vector<pipeline::CommandOutcome> settled() {
    observer.settleRequests(gate);
    return gate.takeOutcomes();
  }

  /// One cycle as the loop runs it, at `state`.
  void cycle(const JointState& state) {
    observer.beforeCycle(index, 0.001 * static_cast<double>(index));
    std::vector<double> torque(static_cast<std::size_t>(wrapper.dof()));
    (void)wrapper.update(state, 0.001, torque);
    hardware::CycleRecord record;
    record.index = index++;
    record.state = &state;
    observer.afterCycle(record);
  }

  pipeline::Wrapper<CartesianCommand> wrapper;
  pipeline::CommandGate gate;
  LiveObserver<CartesianCommand> observer;
  std::uint64_t index = 0;
  const pipeline::SenderId sender{7};
};

TEST_F(LiveObserverRequests, ALifecycleRequestIsSettledOnceCarriedOutInTheOrderSent) {
  const JointState rest = JointState::zero(wrapper.dof());
  cycle(rest);
  ASSERT_TRUE(observer.requestLifecycle(transport::RequestType::kActivate, 1 * kSecond, sender));
  ASSERT_TRUE(observer.requestLifecycle(transport::RequestType::kDeactivate, 2 * kSecond, sender));
  EXPECT_TRUE(settled().empty()) << "settled before the control thread carried it out";
  cycle(rest);  // both, in order: activated, then deactivated
  const std::vector<pipeline::CommandOutcome> outcomes = settled();
  ASSERT_EQ(outcomes.size(), 2U);
  EXPECT_EQ(outcomes[0].stamp_ns, 1 * kSecond);
  EXPECT_EQ(outcomes[1].stamp_ns, 2 * kSecond);
  EXPECT_TRUE(outcomes[0].applied && outcomes[1].applied) << outcomes[0].message;
  EXPECT_EQ(outcomes[0].kind, pipeline::CommandKind::kRequest);
  EXPECT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kInactive);
}

TEST_F(LiveObserverRequests, AnActivationThatFailedIsRefusedWithWhy) {
  JointState broken = JointState::zero(wrapper.dof());
  broken.position[0] = std::numeric_limits<double>::quiet_NaN();
  cycle(broken);  // the last state the control thread saw
  ASSERT_TRUE(observer.requestLifecycle(transport::RequestType::kActivate, 3 * kSecond, sender));
  observer.beforeCycle(index, 0.0);
  const std::vector<pipeline::CommandOutcome> outcomes = settled();
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_FALSE(outcomes[0].applied);
  EXPECT_NE(outcomes[0].message.find("activation failed"), std::string::npos)
      << outcomes[0].message;
  EXPECT_EQ(gate.counts().last_rejection, outcomes[0].message);
  EXPECT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kInactive);
}

TEST_F(LiveObserverRequests, AResetIsSettledWithWhatTheCycleDecided) {
  const JointState rest = JointState::zero(wrapper.dof());
  wrapper.activate(rest);
  const std::uint64_t number = wrapper.reset();
  ASSERT_NE(number, 0U);
  observer.noteReset(number, 4 * kSecond, sender);
  EXPECT_TRUE(settled().empty()) << "settled before a cycle took it";
  cycle(rest);
  const std::vector<pipeline::CommandOutcome> outcomes = settled();
  ASSERT_EQ(outcomes.size(), 1U);
  EXPECT_TRUE(outcomes[0].applied) << "no fault to leave: carried out (the stamp floor cleared)";
  EXPECT_EQ(outcomes[0].stamp_ns, 4 * kSecond);

  // A state the controller cannot use: FAULT, and a reset in it cannot be taken.
  JointState broken = rest;
  broken.position[0] = std::numeric_limits<double>::quiet_NaN();
  cycle(broken);
  ASSERT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kFault);
  observer.noteReset(wrapper.reset(), 5 * kSecond, sender);
  cycle(broken);
  const std::vector<pipeline::CommandOutcome> refused = settled();
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_FALSE(refused[0].applied);
  EXPECT_NE(refused[0].message.find("not usable"), std::string::npos) << refused[0].message;
  EXPECT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kFault);

  observer.noteReset(wrapper.reset(), 6 * kSecond, sender);
  cycle(rest);
  const std::vector<pipeline::CommandOutcome> left = settled();
  ASSERT_EQ(left.size(), 1U);
  EXPECT_TRUE(left[0].applied) << left[0].message;
  EXPECT_EQ(wrapper.diagnostics().state, pipeline::WrapperState::kActive);
}

}  // namespace
}  // namespace comply::host
