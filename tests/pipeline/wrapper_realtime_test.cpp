// update() is the real-time path: wrapper.hpp promises it never allocates or locks. Both are
// measured here on the thread that runs the cycles, by interposing the allocator
// (comply_test_alloc_counter) and pthread_mutex_lock/trylock (mutex_lock_counter.cpp), over
// 10,000 cycles of each wrapper with a moving arm, commands arriving in between, watchdog timeouts
// and FAULT. Submitting is allowed to allocate and lock, so submits happen outside the counting.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>

#include "allocation_counter.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "mutex_lock_counter.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

using comply::testing::AllocationCounter;

constexpr int kCycles = 10'000;
constexpr int kCyclesPerCommand = 1'000;

/// Keeps the optimiser from dropping an allocation or a lock whose result is unused.
template <typename T>
void escape(T* pointer) {
  asm volatile("" : : "g"(pointer) : "memory");
}

/// Allocations and lock attempts of the calling thread inside the measured calls only.
class RealtimeProbe {
 public:
  template <typename Call>
  auto measure(Call&& call) {
    allocation_counter_.start();
    lock_counter_.start();
    auto result = call();
    locks += lock_counter_.stop();
    allocations += allocation_counter_.stop();
    return result;
  }

  std::size_t allocations = 0;
  std::size_t locks = 0;

 private:
  AllocationCounter allocation_counter_;
  MutexLockCounter lock_counter_;
};

// ---- the counters themselves ------------------------------------------------------------------

TEST(RealtimeProbe, CountsLocksOfStdMutexOnThisThreadOnly) {
  std::mutex mutex;
  MutexLockCounter counter;

  counter.start();
  { const std::lock_guard<std::mutex> lock(mutex); }
  EXPECT_EQ(counter.stop(), 1U) << "std::mutex::lock";

  counter.start();
  if (mutex.try_lock()) {
    mutex.unlock();
  }
  EXPECT_EQ(counter.stop(), 1U) << "std::mutex::try_lock";

  { const std::lock_guard<std::mutex> lock(mutex); }
  counter.start();
  EXPECT_EQ(counter.stop(), 0U) << "a lock before start() was counted";

  // Another thread locking while this one counts is not this thread's lock.
  std::atomic<bool> go{false};
  std::atomic<bool> done{false};
  std::thread other([&] {
    while (!go.load()) {
    }
    { const std::lock_guard<std::mutex> lock(mutex); }
    done.store(true);
  });
  counter.start();
  go.store(true);
  while (!done.load()) {
  }
  EXPECT_EQ(counter.stop(), 0U);
  other.join();
}

TEST(RealtimeProbe, SeesTheLocksAndAllocationsOfTheSendersSide) {
  // The same probe must see what submit() and TripleBuffer::write() do, or a zero proves nothing.
  TripleBuffer<int> buffer;
  RealtimeProbe probe;
  probe.measure([&] {
    buffer.write(1);
    return 0;
  });
  EXPECT_EQ(probe.locks, 1U);

  JointWrapper wrapper(fr3Config(kJointImpedancePlugin));
  const JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  JointCommand command = JointCommand::zero(kFr3Dof);
  command.stamp_s = 1.0;
  command.fields = CommandField::kPosition;
  command.position = offset(state.position, 0, 2.0);  // rejected: the message allocates
  RealtimeProbe sender;
  const Verdict verdict = sender.measure([&] { return wrapper.submit(command); });
  EXPECT_FALSE(verdict.accepted);
  EXPECT_GE(sender.locks, 1U) << "the intake mutex";
  EXPECT_GE(sender.allocations, 1U) << "the rejection message";

  RealtimeProbe heap;
  heap.measure([] {
    auto* value = new int(7);
    escape(value);
    delete value;
    return 0;
  });
  EXPECT_EQ(heap.allocations, 1U);
}

// ---- update() ---------------------------------------------------------------------------------

/// A smooth motion around home, different on every joint, so the model and the laws see new
/// numbers every cycle.
JointState movingState(const JointVector& home, int cycle) {
  return test::movingState(home, cycle, 0.05, 0.5);
}

std::string realtimeLines(const std::string& behavior) {
  // A timeout shorter than the gap between commands, so the watchdog fires in every gap.
  return "command_timeout_s: 0.2\ntimeout_behavior: " + behavior +
         "\ncompensation:\n  friction:\n    model: sigmoid\n";
}

/// The gain stage on, its tank started low so that it both refuses and refills (the ratio-mode
/// damping bound factorises the mass matrix) in the counted cycles; the momentum observer; the
/// force stage's contact limits (the force axes come with the commands).
const std::string kGuardedLines =
    "gain_ramps:\n  enabled: true\npassivity:\n  enabled: true\n  tank_initial_j: 0.02\n"
    "observer:\n  enabled: true\nforce_control:\n  contact_force_limit_n: [0.0, 2.0, 0.0]\n"
    "  contact_torque_limit_n_m: [0.0, 0.0, 0.2]\n";

/// Walls across the FR3's home TCP (x 0.307, z 0.487 m: the replayed arm moves a few cm around
/// it), so that the reference is projected and the barrier brakes in the counted cycles.
const std::string kWallLines =
    "walls:\n  - {point: [0.3, 0.0, 0.0], normal: [1.0, 0.0, 0.0]}\n"
    "boxes:\n  - {min: [-1.0, -1.0, 0.49], max: [1.0, 1.0, 1.5]}\n";

/// A contact force limit so low (20 N into the hands' 75 N/mm: v_max about 4 cm/s) that the
/// replayed arm's TCP, up to a few cm/s faster, is both scaled and braked in the counted cycles.
const std::string kContactSpeedLines = "contact_speed:\n  enabled: true\n  force_limit_n: 20\n";

/// The lines of a realtime run: "hold" and "reanchor" as realtimeLines(); "hold+gains" holds
/// with every guard on (kGuardedLines).
std::string realtimeConfigLines(const std::string& behavior) {
  if (behavior == "hold+walls") {
    return realtimeLines("hold") + kWallLines;
  }
  if (behavior == "hold+contact") {
    return realtimeLines("hold") + kContactSpeedLines;
  }
  return behavior == "hold+gains" ? realtimeLines("hold") + kGuardedLines : realtimeLines(behavior);
}

void expectTheGuardWorked(const DiagnosticsSnapshot& diagnostics) {
  EXPECT_TRUE(diagnostics.passivity.enabled);
  EXPECT_GT(diagnostics.passivity.injected_j, 0.0) << "the tank paid for nothing";
  EXPECT_GT(diagnostics.passivity.dissipated_j, 0.0) << "the tank was never refilled";
}

/// kCycles counted update() calls of an active `wrapper` at a moving state, `between(cycle)`
/// before each, uncounted (submitting is allowed to allocate and lock): none allocates or locks,
/// every one is kOk.
template <typename WrapperType, typename Between>
void expectRealtimeLoop(WrapperType& wrapper, Between&& between) {
  const JointVector home = fr3Home();
  RealtimeProbe probe;
  TorqueBuffer torque;
  int not_ok = 0;
  for (int cycle = 1; cycle <= kCycles; ++cycle) {
    between(cycle);
    if (::testing::Test::HasFatalFailure()) {
      return;
    }
    const JointState state = movingState(home, cycle);
    const CycleStatus status =
        probe.measure([&] { return wrapper.update(state, kPeriod, torque.span()); });
    not_ok += status != CycleStatus::kOk;
  }
  EXPECT_EQ(probe.allocations, 0U);
  EXPECT_EQ(probe.locks, 0U);
  EXPECT_EQ(not_ok, 0);
}

/// Runs kCycles counted update() calls of an activated `wrapper`, submitting `commandAt(cycle)`
/// (uncounted) every kCyclesPerCommand cycles; `look()` (uncounted) before every cycle.
template <typename WrapperType, typename CommandAt, typename Look = void (*)()>
void expectRealtimeCycles(
    WrapperType& wrapper, CommandAt commandAt, Look look = [] {}) {
  wrapper.activate(movingState(fr3Home(), 0));
  expectRealtimeLoop(wrapper, [&](int cycle) {
    look();
    if (cycle % kCyclesPerCommand == kCyclesPerCommand / 2) {
      const Verdict verdict = wrapper.submit(commandAt(cycle));
      ASSERT_TRUE(verdict.accepted) << "cycle " << cycle << ": " << verdict.message;
    }
  });
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.commands_accepted, static_cast<std::uint64_t>(kCycles / kCyclesPerCommand));
  EXPECT_GE(diagnostics.watchdog_timeouts, static_cast<std::uint64_t>(kCycles / kCyclesPerCommand))
      << "the timeout path did not run";
}

// The gate's control-thread side: noting the command in force after every cycle, with the intake
// offering and settling commands between cycles, as a live host does.
TEST(WrapperRealtime, TheGatesCycleSideNeitherAllocatesNorLocks) {
  CommandGate gate({.kind = CommandKind::kJoint, .publisher_timeout_s = 0.5});
  RealtimeProbe probe;
  std::uint64_t accepted = 0;
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    if (cycle % 10 == 0) {
      Offer offer;
      offer.stamp_ns = static_cast<std::int64_t>(cycle + 1) * 1'000'000;
      offer.kind = CommandKind::kJoint;
      offer.publisher = 1;
      gate.offer(offer, true, [&](std::int64_t) { return Verdict{.sequence = ++accepted}; });
    }
    const CommandId in_force{.sequence = accepted};
    EXPECT_TRUE(probe.measure(
        [&] { return gate.noteCycle(cycle, in_force, [cycle] { return std::int64_t{cycle}; }); }));
    if (cycle % 100 == 0) {
      gate.settle();
      gate.takeOutcomes();
    }
  }
  gate.settle();
  EXPECT_EQ(gate.counts().applied, static_cast<std::uint64_t>(kCycles / 10));
  EXPECT_EQ(probe.allocations, 0U);
  EXPECT_EQ(probe.locks, 0U);
}

TEST(WrapperRealtime, JointUpdateNeitherAllocatesNorLocks) {
  for (const std::string behavior : {"hold", "reanchor", "hold+gains"}) {
    SCOPED_TRACE(behavior);
    const bool guarded = behavior == "hold+gains";
    JointWrapper wrapper(fr3Config(kJointImpedancePlugin, realtimeConfigLines(behavior)));
    const JointVector home = fr3Home();
    expectRealtimeCycles(wrapper, [&](int cycle) {
      // Position, velocity and gains together, near where the arm is.
      JointCommand command = JointCommand::zero(kFr3Dof);
      command.stamp_s = cycle * kPeriod;
      command.fields = CommandField::kPosition | CommandField::kVelocity |
                       CommandField::kStiffness | CommandField::kDamping;
      command.position = movingState(home, cycle).position;
      command.velocity.setConstant(0.01);
      command.stiffness.setConstant(cycle % 2000 < 1000 ? 100.0 : 300.0);
      command.damping.setConstant(10.0);
      return command;
    });
    if (behavior == "hold+walls") {
      // The walls stage ran in the counted cycles: reference projected, barrier braking.
      EXPECT_GT(wrapper.diagnostics().wall_reference_hits, 0U);
      EXPECT_GT(wrapper.diagnostics().wall_brake_hits, 0U);
    }
    if (guarded) {
      expectTheGuardWorked(wrapper.diagnostics());
      // The observer ran in the counted cycles (the replayed state moves with no torque behind
      // it: all of it is "external").
      const auto& observer = wrapper.controller().observer();
      EXPECT_TRUE(observer.wrench().allFinite());
      EXPECT_GT(observer.jointTorque().norm(), 0.0);
    }
  }
}

TEST(WrapperRealtime, CartesianUpdateNeitherAllocatesNorLocks) {
  for (const std::string behavior :
       {"hold", "reanchor", "hold+gains", "hold+walls", "hold+contact"}) {
    SCOPED_TRACE(behavior);
    const bool guarded = behavior == "hold+gains";
    CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, realtimeConfigLines(behavior)));
    bool ratio = true;
    double largest_push = 0.0;  // of the force stage, seen between the counted cycles
    int scaled = 0;             // cycles the contact-speed stage scaled the law, and braked
    int braked = 0;
    const auto look = [&] {
      largest_push =
          std::max(largest_push, std::abs(wrapper.controller().forceAxes().forceCommand()[2]));
      const ContactSpeed& contact = wrapper.controller().contactSpeed();
      scaled += contact.share() > 0.0 && contact.share() < 1.0 ? 1 : 0;
      braked += contact.brakeForce() > 0.0 ? 1 : 0;
    };
    expectRealtimeCycles(
        wrapper,
        [&](int cycle) {
          // Pose and twist near the measured TCP; damping alternates between the ratio mode (mass
          // matrix and double diagonalisation) and absolute blocks.
          const model::Data& measured = wrapper.controller().modelData();
          CartesianCommand command = CartesianCommand::zero(kFr3Dof);
          command.stamp_s = cycle * kPeriod;
          command.fields = CommandField::kPosition | CommandField::kVelocity |
                           CommandField::kDamping | CommandField::kStiffness;
          command.position = measured.tip_position + Eigen::Vector3d(0.01, 0.0, -0.01);
          command.orientation = measured.tip_orientation;
          command.twist[1] = 0.02;
          command.stiffness_translational =
              (cycle % 2000 < 1000 ? 400.0 : 1200.0) * Eigen::Matrix3d::Identity();
          command.task_frame =
              Eigen::AngleAxisd(cycle % 3000 < 1500 ? 0.0 : 0.5, Eigen::Vector3d::UnitZ()) *
              Eigen::Quaterniond::Identity();
          command.fields = command.fields | CommandField::kTaskFrame;
          command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
          command.damping_mode = ratio ? DampingMode::kRatio : DampingMode::kAbsolute;
          command.damping_translational = 45.0 * Eigen::Matrix3d::Identity();
          command.damping_rotational = 3.0 * Eigen::Matrix3d::Identity();
          ratio = !ratio;
          if (guarded) {
            // Force along task z throughout, about task x every other command.
            command.fields = command.fields | CommandField::kForce;
            command.force_axes << 0.0, 0.0, 1.0, ratio ? 1.0 : 0.0, 0.0, 0.0;
            command.wrench_target << 0.0, 0.0, 3.0, 0.2, 0.0, 0.0;
          }
          return command;
        },
        look);
    if (behavior == "hold+walls") {
      // The walls stage ran in the counted cycles: reference projected, barrier braking.
      EXPECT_GT(wrapper.diagnostics().wall_reference_hits, 0U);
      EXPECT_GT(wrapper.diagnostics().wall_brake_hits, 0U);
    }
    if (behavior == "hold+contact") {
      // The contact-speed stage ran in the counted cycles: the law scaled, and the TCP braked.
      EXPECT_GT(wrapper.diagnostics().contact_speed_hits, 0U);
      EXPECT_GT(scaled, 0);
      EXPECT_GT(braked, 0);
    }
    if (guarded) {
      expectTheGuardWorked(wrapper.diagnostics());
      // The force stage ran in the counted cycles.
      EXPECT_GT(largest_push, 0.0);
      // The observer ran in the counted cycles (the replayed state moves with no torque behind
      // it: all of it is "external").
      const auto& observer = wrapper.controller().observer();
      EXPECT_TRUE(observer.wrench().allFinite());
      EXPECT_GT(observer.jointTorque().norm(), 0.0);
    }
  }
}

// ---- timed chunks -----------------------------------------------------------------------------

/// A chunk of 16 waypoints 25 ms apart from `now_s`, around the measured pose, with stiffness,
/// damping, task frame and feedforward moving along it.
CartesianChunk movingChunk(const model::Data& measured, double now_s, double stamp_s) {
  CartesianChunk chunk;
  chunk.stamp_s = stamp_s;
  chunk.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping |
                 CommandField::kTaskFrame | CommandField::kWrenchFeedforward;
  for (int k = 0; k < 16; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{now_s + 0.025 * (k - 2),
                                             CartesianCommand::zero(kFr3Dof)};
    CartesianCommand& c = waypoint.command;
    c.position = measured.tip_position + Eigen::Vector3d(0.002 * k, 0.001 * (k % 3), 0.0);
    c.orientation = measured.tip_orientation;
    c.stiffness_translational = (400.0 + 50.0 * k) * Eigen::Matrix3d::Identity();
    c.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
    c.damping_mode = DampingMode::kRatio;
    c.task_frame =
        Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitZ()) * Eigen::Quaterniond::Identity();
    c.wrench_feedforward[2] = 0.1 * k;
    chunk.waypoints.push_back(waypoint);
  }
  return chunk;
}

// Chunks taking over from each other and from single commands, every other one at its waypoint 3
// (waiting for it), played with the gain stage and the observer on, a command on the chunk's
// groups ending one, the watchdog after the last; the intake predicting between cycles.
TEST(WrapperRealtime, PlayingChunksNeitherAllocatesNorLocks) {
  // Each chunk is planned around where the replayed arm, moving on its own, is measured: its
  // 1 mm zigzag and the blends from the chunk before ask 13 m/s^2 and 25 rad/s^2 of the reference,
  // at the intake's limits (chunk_limits_test.cpp has them), which are off here.
  CartesianWrapper wrapper(
      fr3Config(kCartesianImpedancePlugin, realtimeLines("hold") + kGuardedLines +
                                               "validation:\n  max_chunk_acceleration_m_per_s2: 0\n"
                                               "  max_chunk_angular_acceleration_rad_per_s2: 0\n"));
  wrapper.activate(movingState(fr3Home(), 0));
  int chunks = 0;
  int deferred_takeovers = 0;
  std::vector<CartesianCommand> predicted;
  const std::vector<double> ahead_s{0.0, 0.01, 0.02, 0.03};
  expectRealtimeLoop(wrapper, [&](int cycle) {
    const double now_s = cycle * kPeriod;  // the host's clock: the controller's since activation
    const model::Data& measured = wrapper.controller().modelData();
    for (const ChunkTiming& timing : wrapper.controller().chunks().events()) {
      deferred_takeovers +=
          timing.end == ChunkEnd::kTookOver && std::isfinite(timing.requested_takeover_s) ? 1 : 0;
    }
    if (cycle < kCycles - 1000 && cycle % 150 == 75) {
      CartesianChunk chunk = movingChunk(measured, now_s, now_s);
      if (chunks % 2 == 1) {
        chunk.takeover_s = chunk.waypoints[3].time_s;
      }
      const Verdict verdict = wrapper.submitChunk(chunk, now_s);
      ASSERT_TRUE(verdict.accepted) << "cycle " << cycle << ": " << verdict.message;
      ++chunks;
    }
    if (cycle % 50 == 0) {
      std::vector<double> times;
      for (const double dt : ahead_s) {
        times.push_back(now_s + dt);
      }
      (void)wrapper.predict(times, now_s, predicted);
      ASSERT_EQ(predicted.size(), times.size());
    }
    if (cycle % 1000 == 500) {  // the chunk's own group: ends it
      CartesianCommand command = CartesianCommand::zero(kFr3Dof);
      command.stamp_s = now_s + 1e-4;
      command.fields = CommandField::kPosition;
      command.position = measured.tip_position;
      command.orientation = measured.tip_orientation;
      ASSERT_TRUE(wrapper.submit(command).accepted);
    }
  });
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.commands_accepted, static_cast<std::uint64_t>(chunks + kCycles / 1000));
  EXPECT_GE(diagnostics.watchdog_timeouts, 1U) << "the watchdog never followed a chunk's end";
  EXPECT_GE(deferred_takeovers, 3) << "no chunk took over at its waypoint";
  expectTheGuardWorked(diagnostics);
}

// Warming between cycles (ControlLoop's warm_ahead_s) neither changes a torque, bit for bit,
// nor allocates or locks.
TEST(WrapperRealtime, WarmingChangesNoTorqueAndNeitherAllocatesNorLocks) {
  const std::string lines = realtimeLines("hold") + kGuardedLines;
  CartesianWrapper cold(fr3Config(kCartesianImpedancePlugin, lines));
  CartesianWrapper warmed(fr3Config(kCartesianImpedancePlugin, lines));
  const JointVector home = fr3Home();
  cold.activate(movingState(home, 0));
  warmed.activate(movingState(home, 0));
  RealtimeProbe probe;
  TorqueBuffer cold_torque;
  TorqueBuffer warm_torque;
  JointState last = movingState(home, 0);
  int differing = 0;
  for (int cycle = 1; cycle <= 2000; ++cycle) {
    if (cycle % 500 == 250) {
      CartesianCommand command = CartesianCommand::zero(kFr3Dof);
      command.stamp_s = cycle * kPeriod;
      command.fields = CommandField::kPosition | CommandField::kStiffness;
      command.position = cold.controller().modelData().tip_position + Eigen::Vector3d(0.01, 0, 0);
      command.orientation = cold.controller().modelData().tip_orientation;
      command.stiffness_translational = (300.0 + cycle) * Eigen::Matrix3d::Identity();
      command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
      ASSERT_TRUE(cold.submit(command).accepted);
      ASSERT_TRUE(warmed.submit(command).accepted);
    }
    probe.measure([&] {
      warmed.warm(last);
      warmed.warm(movingState(home, cycle + 7));  // not the state it computed: ignored
      return 0;
    });
    const JointState state = movingState(home, cycle);
    cold.update(state, kPeriod, cold_torque.span());
    warmed.update(state, kPeriod, warm_torque.span());
    differing += cold_torque.values != warm_torque.values ? 1 : 0;
    last = state;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(probe.allocations, 0U);
  EXPECT_EQ(probe.locks, 0U);
}

// ---- output modes -----------------------------------------------------------------------------

// joint_pd and admittance (position, velocity) for both kinds of law: the split for a PD drive,
// the virtual arm with a wrist wrench and a declared payload, its bounds, and FAULT on a NaN state
// (the position hold) and back after a reset, all in counted cycles.
TEST(WrapperRealtime, EveryOutputModeNeitherAllocatesNorLocks) {
  for (const std::string mode : {"joint_pd", "position", "velocity"}) {
    for (const bool cartesian : {false, true}) {
      SCOPED_TRACE(mode + (cartesian ? " Cartesian" : " joint"));
      const std::string lines =
          realtimeLines("hold") +
          "  payload:\n    enabled: true\n    mass_kg: 1.5\n    com_m: [0.0, 0.0, 0.05]\n"
          "output:\n  mode: " +
          mode +
          "\n  admittance:\n    added_mass_kg: [1.0, 2.0, 3.0]\n"
          // The reading below carries no tool: the rest check (counted in its own test below) is
          // given room.
          "wrench_sensor:\n  rest_force_tolerance_n: 100.0\n  rest_torque_tolerance_n_m: 10.0\n";
      const auto run = [&](auto& wrapper) {
        const JointVector home = fr3Home();
        wrapper.activate(movingState(home, 0));
        RealtimeProbe probe;
        ActuatorCommand command;
        command.resize(kFr3Dof);
        int wrote = 0;
        int faults = 0;
        for (int cycle = 1; cycle <= kCycles; ++cycle) {
          JointState state = movingState(home, cycle);
          state.wrench_valid = true;
          state.wrench << 3.0 * std::sin(cycle * 1e-3), 1.0, -2.0, 0.1, 0.0, 0.2;
          if (cycle % 2500 == 1000) {
            state.position[cycle % kFr3Dof] = std::numeric_limits<double>::quiet_NaN();
          }
          if (cycle % 2500 == 1100) {
            wrapper.reset();  // uncounted: the intake's side
          }
          wrote += probe.measure([&] { return wrapper.cycle(state, kPeriod, command); }) ? 1 : 0;
          faults += wrapper.diagnostics().state == WrapperState::kFault ? 1 : 0;
          EXPECT_TRUE(command.position.allFinite() && command.velocity.allFinite() &&
                      command.effort.allFinite())
              << "cycle " << cycle;
        }
        EXPECT_EQ(wrote, kCycles) << "an active wrapper writes in every mode, FAULT included";
        EXPECT_GT(faults, 0) << "the FAULT path did not run";
        EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kActive) << "no way back";
        EXPECT_EQ(probe.allocations, 0U);
        EXPECT_EQ(probe.locks, 0U);
      };
      if (cartesian) {
        CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, lines));
        run(wrapper);
      } else {
        JointWrapper wrapper(fr3Config(kJointImpedancePlugin, lines));
        run(wrapper);
      }
    }
  }
}

// The wrist sensor's checks (sensor_check.hpp) in counted cycles: the rest check's FAULT with its
// message, the cycles after a tare and a reset pass it, and the comparison with the momentum
// observer up to its own FAULT.
TEST(WrapperRealtime, TheWristSensorChecksNeitherAllocateNorLock) {
  RealtimeProbe probe;
  TorqueBuffer torque;
  const auto cycles = [&](auto& wrapper, const JointState& state, int count) {
    int faults = 0;
    for (int cycle = 0; cycle < count; ++cycle) {
      faults += probe.measure([&] { return wrapper.update(state, kPeriod, torque.span()); }) ==
                CycleStatus::kFault;
    }
    return faults;
  };
  {
    CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin,
                                       "compensation:\n  payload:\n    enabled: true\n"
                                       "    mass_kg: 1.5\n    com_m: [0.0, 0.0, 0.05]\n"));
    JointState state = restingAt(wrapper.controller(), fr3Home());
    state.wrench_valid = true;  // zero: the declared tool is not on the sensor
    wrapper.activate(state);
    EXPECT_EQ(cycles(wrapper, state, 10), 10);
    ASSERT_EQ(wrapper.tare(), "");  // uncounted: the intake's side
    EXPECT_EQ(cycles(wrapper, state, 1), 1);
    wrapper.reset();
    EXPECT_EQ(cycles(wrapper, state, 100), 0);
  }
  {
    CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin,
                                       "observer:\n  enabled: true\n  measured_torque: true\n"
                                       "wrench_sensor:\n  observer_tolerance_n: 1.0\n"));
    JointState state = restingAt(wrapper.controller(), fr3Home());
    state.wrench_valid = true;
    state.wrench[1] = 5.0;  // a bias the observer does not see
    wrapper.activate(state);
    EXPECT_GT(cycles(wrapper, state, 1000), 500);
    EXPECT_NE(wrapper.diagnostics().last_fault.find("momentum observer"), std::string::npos)
        << wrapper.diagnostics().last_fault;
  }
  EXPECT_EQ(probe.allocations, 0U);
  EXPECT_EQ(probe.locks, 0U);
}

// ---- the contact reflex ------------------------------------------------------------------------

// The reflex armed on the observer's wrench, its thresholds within what the replayed motion (no
// torque behind it: all of it "external") gives: it trips, holds or retreats (or faults), and a
// reset every 500 cycles re-arms it, while commands keep coming (refused while it holds).
TEST(WrapperRealtime, TheContactReflexTrippingNeitherAllocatesNorLocks) {
  for (const std::string reaction : {"hold", "retreat", "fault"}) {
    SCOPED_TRACE(reaction);
    CartesianWrapper wrapper(
        fr3Config(kCartesianImpedancePlugin,
                  realtimeLines("hold") + "observer:\n  enabled: true\nreflex:\n  enabled: true\n" +
                      "  reaction: " + reaction +
                      "\n  force_n: 0.5\n  torque_nm: 0.05\n  hold_stiffness_fraction: 0.5\n"));
    const JointVector home = fr3Home();
    wrapper.activate(movingState(home, 0));
    RealtimeProbe probe;
    TorqueBuffer torque;
    int refused = 0;
    for (int cycle = 1; cycle <= kCycles; ++cycle) {
      if (cycle % 500 == 0) {
        ASSERT_NE(wrapper.reset(), 0U);
      }
      if (cycle % 100 == 50) {
        const model::Data& measured = wrapper.controller().modelData();
        CartesianCommand command = CartesianCommand::zero(kFr3Dof);
        command.stamp_s = cycle * kPeriod;
        command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kReflex;
        command.position = measured.tip_position + Eigen::Vector3d(0.01, 0.0, -0.01);
        command.orientation = measured.tip_orientation;
        command.twist[1] = 0.02;
        command.reflex_force = Eigen::Vector3d(0.0, 0.0, 0.8);
        refused += wrapper.submit(command).reason == RejectionReason::kReflexLatched ? 1 : 0;
      }
      const JointState state = movingState(home, cycle);
      (void)probe.measure([&] { return wrapper.update(state, kPeriod, torque.span()); });
    }
    const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
    // It tripped after every reset (and once before the first).
    EXPECT_GE(diagnostics.reflex_trips, static_cast<std::uint64_t>(kCycles / 500));
    if (reaction == "fault") {
      EXPECT_EQ(diagnostics.faults, diagnostics.reflex_trips);
    } else {
      EXPECT_GT(refused, 0);
    }
    EXPECT_EQ(probe.allocations, 0U);
    EXPECT_EQ(probe.locks, 0U);
  }
}

// ---- FAULT ------------------------------------------------------------------------------------

/// Counted cycles at a moving state; returns how many were not `expected`.
template <typename WrapperType>
int countedCycles(WrapperType& wrapper, RealtimeProbe& probe, int first, int count,
                  CycleStatus expected, bool nan_state = false) {
  const JointVector home = fr3Home();
  TorqueBuffer torque;
  int unexpected = 0;
  for (int cycle = first; cycle < first + count; ++cycle) {
    JointState state = movingState(home, cycle);
    if (nan_state) {
      state.velocity[cycle % kFr3Dof] = std::numeric_limits<double>::quiet_NaN();
    }
    const CycleStatus status =
        probe.measure([&] { return wrapper.update(state, kPeriod, torque.span()); });
    unexpected += status != expected;
  }
  return unexpected;
}

TEST(WrapperRealtime, CyclesInFaultNeitherAllocateNorLock) {
  // A Cartesian law that fails in the cycle once ratios are streamed (see wrapper_fault_test).
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin,
                                     "plugin_parameters:\n  inertia_aware_damping: 0\n"
                                     "initial:\n  damping_mode: absolute\n"));
  wrapper.activate(movingState(fr3Home(), 0));
  RealtimeProbe probe;
  EXPECT_EQ(countedCycles(wrapper, probe, 1, 100, CycleStatus::kOk), 0);

  CartesianCommand ratio = CartesianCommand::zero(kFr3Dof);
  ratio.stamp_s = 1.0;
  ratio.fields = CommandField::kDamping;
  ratio.damping_mode = DampingMode::kRatio;
  ASSERT_TRUE(wrapper.submit(ratio).accepted);
  // Entering FAULT (error text included) and staying in it.
  EXPECT_EQ(countedCycles(wrapper, probe, 101, 1000, CycleStatus::kFault), 0);

  CartesianCommand absolute = ratio;
  absolute.stamp_s = 2.0;
  absolute.damping_mode = DampingMode::kAbsolute;
  ASSERT_TRUE(wrapper.submit(absolute).accepted);
  wrapper.reset();
  EXPECT_EQ(countedCycles(wrapper, probe, 1101, 100, CycleStatus::kOk), 0);

  // An unusable joint state: FAULT from the first half of the cycle.
  EXPECT_EQ(countedCycles(wrapper, probe, 1201, 1000, CycleStatus::kFault, /*nan_state=*/true), 0);

  EXPECT_EQ(wrapper.diagnostics().faults, 2U);
  EXPECT_EQ(probe.allocations, 0U);
  EXPECT_EQ(probe.locks, 0U);
}

}  // namespace
}  // namespace comply::pipeline::test
