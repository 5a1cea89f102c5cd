// Whether the wrist sensor can be trusted (sensor_check.hpp), in MuJoCo, each run a couple of
// seconds:
//   - a declared 3 kg tool that is not mounted reads as a push of its weight upward: an idle
//     admittance arm (UR5e, position drives) rose by centimetres before; the rest check now
//     faults it before it moves, naming the declared and the measured mass; a tool declared as
//     mounted activates;
//   - a wrist sensor biased along the contact's direction shifts what the contact-force limit
//     sees: the FR3 pressing a table through a 20 N limit pressed 20 N plus the bias; the bias
//     at activation is now a FAULT before the arm moves, and a bias that drifts in after
//     activation is caught against the momentum observer.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "output_modes/output_mode_rig.hpp"
#include "sim_support.hpp"
#include "surface_following/fixture.hpp"

namespace comply::testing {
namespace {

using Rig = experiments::OutputModeRig<CartesianCommand>;
using pipeline::WrapperState;

constexpr double kToolKg = 3.0;
constexpr double kToolComM = 0.05;  // examples/sim/payload_3kg.xml: along TCP z

/// The UR5e on position drives in admittance (config/sim/cartesian_impedance.yaml), declaring
/// the 3 kg tool; `mounted`: the tool is on the plant's flange.
struct IdleRun {
  double tcp_travel_m = 0.0;  ///< largest distance of the TCP from where it started
  bool faulted = false;
  std::string fault;
};

IdleRun idleAdmittanceArm(bool mounted, double rest_force_tolerance_n) {
  pipeline::WrapperConfig config = experiments::outputModeConfig("ur5e", OutputMode::kPosition);
  config.payload_compensation = true;
  config.payload.mass_kg = kToolKg;
  config.payload.com_in_tip = Eigen::Vector3d(0.0, 0.0, kToolComM);
  config.wrench_sensor.rest_force_tolerance_n = rest_force_tolerance_n;
  sim::PlantOptions options = experiments::plantOf(OutputMode::kPosition);
  if (mounted) {
    options.scene.tool = kSourceDir / "examples" / "sim" / "payload_3kg.xml";
  }
  Rig rig(config, options);
  const Eigen::Vector3d start = rig.plant.tcpPose().translation();
  IdleRun run;
  for (int cycle = 0; cycle < 2000; ++cycle) {  // 2 s, no command: the arm is idle
    (void)rig.cycle();
    run.tcp_travel_m =
        std::max(run.tcp_travel_m, (rig.plant.tcpPose().translation() - start).norm());
  }
  const pipeline::DiagnosticsSnapshot diagnostics = rig.wrapper.diagnostics();
  run.faulted = diagnostics.faults > 0;
  run.fault = diagnostics.last_fault;
  return run;
}

TEST(SensorTrust, ADeclaredToolThatIsNotMountedFaultsAnIdleAdmittanceArmBeforeItMoves) {
  // The check out of the way (a tolerance above the tool's weight): the arm rises.
  const IdleRun unchecked = idleAdmittanceArm(false, 1e3);
  EXPECT_GT(unchecked.tcp_travel_m, 5e-3) << "the missing tool's weight did not move the arm?";
  const IdleRun checked = idleAdmittanceArm(false, 2.0);
  EXPECT_TRUE(checked.faulted);
  EXPECT_LT(checked.tcp_travel_m, 1e-3);
  EXPECT_NE(checked.fault.find("wrist sensor: the declared tool"), std::string::npos)
      << checked.fault;
  EXPECT_NE(checked.fault.find("mass_kg 3.00 kg"), std::string::npos) << checked.fault;
  EXPECT_NE(checked.fault.find("0.00 kg along gravity"), std::string::npos) << checked.fault;
  std::printf(
      "3 kg declared, not mounted: the idle admittance arm moved %.1f mm unchecked, "
      "%.3f mm with the check (%s)\n",
      1e3 * unchecked.tcp_travel_m, 1e3 * checked.tcp_travel_m, checked.fault.c_str());
}

TEST(SensorTrust, ADeclaredToolThatIsMountedActivates) {
  const IdleRun mounted = idleAdmittanceArm(true, 2.0);
  EXPECT_FALSE(mounted.faulted) << mounted.fault;
  EXPECT_LT(mounted.tcp_travel_m, 1e-3);
}

// ---- the contact-force limit on a biased sensor ---------------------------------------------

constexpr double kLimitN = 20.0;
constexpr double kBiasN = 8.0;       // along the sensor's z, which points down into the table
constexpr double kProbeTipM = 0.11;  // examples/sim/probe_tool.xml: the ball's bottom below the TCP

/// A rigid table 1 cm under the probe's tip at `tcp` (the FR3's home points the TCP down).
std::filesystem::path tableUnder(const Eigen::Vector3d& tcp) {
  const double top = tcp.z() - kProbeTipM - 0.01;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("comply_sensor_trust_table_" + std::to_string(::getpid()) + ".xml");
  std::ofstream(file) << "<mujocoinclude>\n  <body name=\"table\" pos=\"" << tcp.x() << " "
                      << tcp.y() << " " << top / 2.0
                      << "\">\n    <geom name=\"table_top\" type=\"box\" size=\"0.1 0.1 "
                      << top / 2.0
                      << "\" friction=\"0.3 0.005 0.0001\" solref=\"0.005 1\"/>\n  </body>\n"
                         "</mujocoinclude>\n";
  return file;
}

/// The FR3 (torque) with the probe over a table, 1500 N/m, a 20 N limit along task z (down),
/// read from the sensor, or with `observer_tolerance_n` > 0 compared with the observer.
struct PressRig {
  PressRig(const Vector6d& sensor_offset, double rest_force_tolerance_n,
           double observer_tolerance_n) {
    config = simCartesianConfig("fr3");
    config.initial_cartesian.stiffness_translational = 1500.0 * Eigen::Matrix3d::Identity();
    config.force_control.source = pipeline::ForceSource::kSensor;
    config.force_control.contact_force_limit_n = Eigen::Vector3d(0.0, 0.0, kLimitN);
    config.wrench_sensor.filter_hz = 50.0;  // the reading chatters with the contact
    config.wrench_sensor.rest_force_tolerance_n = rest_force_tolerance_n;
    config.wrench_sensor.observer_tolerance_n = observer_tolerance_n;
    config.observer.enabled = observer_tolerance_n > 0.0;
    config.observer.measured_torque = true;
    // The probe (60 g) is the tool beyond the sensor, declared: its weight is compensated and
    // comes off the reading.
    config.payload_compensation = true;
    config.payload.mass_kg = experiments::surface_following::kProbeMassKg;
    config.payload.com_in_tip =
        Eigen::Vector3d(0.0, 0.0, experiments::surface_following::kProbeComM);
    options.substeps = 2;
    options.link_side_torque = true;
    options.wrench_sensor_offset = sensor_offset;
    options.scene.tool = kSourceDir / "examples" / "sim" / "probe_tool.xml";
  }
  pipeline::WrapperConfig config;
  sim::PlantOptions options;
};

struct PressRun {
  double settled_n = 0.0;  ///< the table's push, mean of the last 0.3 s [N]
  double peak_n = 0.0;     ///< after the first touch's transient
  double tcp_travel_m = 0.0;
  bool faulted = false;
  std::string fault;
};

/// Presses the reference 5 cm into the table over 1 s and holds it there until 2.5 s; a bias of
/// `drift_n` down the sensor's z (base -z) ramps into the reading from 1 s to 2 s.
PressRun pressThroughTheLimit(PressRig setup, double drift_n = 0.0) {
  Eigen::Vector3d home_tcp;
  {
    const sim::SimulatedRobot probe(*setup.config.robot_description, sim::PlantOptions{});
    home_tcp = probe.tcpPose().translation();
  }
  setup.options.scene.objects = {tableUnder(home_tcp)};
  Rig rig(setup.config, setup.options);
  const MeasuredPose home = rig.wrapper.measuredPose();
  PressRun run;
  std::array<double, 20> window{};  // the table's push, a 20 ms mean (the rigid contact chatters)
  double settled_sum = 0.0;
  int settled = 0;
  int touch = -1;
  int fault = -1;
  // Until 2.5 s, or 0.5 s after a FAULT (the hold keeps the arm where it stopped).
  for (int cycle = 0; cycle < 2500 && (fault < 0 || cycle < fault + 500); ++cycle) {
    CartesianCommand command = CartesianCommand::zero(rig.wrapper.dof());
    command.stamp_s = (cycle + 1) * experiments::kRigPeriodS;
    command.fields = CommandField::kPosition | CommandField::kTaskFrame;
    command.orientation = home.tcp_orientation;
    command.task_frame = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
    command.position =
        home.tcp_position - std::clamp(cycle / 1000.0, 0.0, 1.0) * Eigen::Vector3d(0.0, 0.0, 0.06);
    const pipeline::Verdict verdict = rig.wrapper.submit(command);
    if (!run.faulted) {
      EXPECT_TRUE(verdict.accepted) << verdict.message;
    }
    rig.read();
    rig.state.wrench[2] -= drift_n * std::clamp((cycle - 1000) / 1000.0, 0.0, 1.0);
    if (rig.wrapper.cycle(rig.state, experiments::kRigPeriodS, rig.command)) {
      (void)rig.plant.writeCommand(rig.command);
    }
    rig.plant.step();
    window[static_cast<std::size_t>(cycle) % window.size()] = rig.plant.toolContactWrench()[2];
    const double table_n =
        std::accumulate(window.begin(), window.end(), 0.0) / static_cast<double>(window.size());
    if (touch < 0 && table_n > 0.5) {
      touch = cycle;
    }
    if (touch >= 0 && cycle > touch + 300) {
      run.peak_n = std::max(run.peak_n, table_n);
    }
    if (fault < 0 && rig.wrapper.diagnostics().state == WrapperState::kFault) {
      fault = cycle;
      run.faulted = true;
    }
    if (cycle >= 2200) {
      settled_sum += table_n;
      ++settled;
    }
    run.tcp_travel_m =
        std::max(run.tcp_travel_m,
                 (rig.plant.tcpPose().translation() - Eigen::Vector3d(home.tcp_position)).norm());
  }
  run.settled_n = settled > 0 ? settled_sum / settled : 0.0;
  const pipeline::DiagnosticsSnapshot diagnostics = rig.wrapper.diagnostics();
  run.faulted = diagnostics.faults > 0;
  run.fault = diagnostics.last_fault;
  return run;
}

Vector6d biasDown() {
  Vector6d bias = Vector6d::Zero();
  bias[2] = kBiasN;  // the sensor's z points down at home: the reading reads the table 8 N short
  return bias;
}

TEST(SensorTrust, ABiasedSensorFaultsBeforeItsContactLimitIsTrusted) {
  const PressRun clean = pressThroughTheLimit(PressRig(Vector6d::Zero(), 2.0, 0.0));
  EXPECT_FALSE(clean.faulted) << clean.fault;
  EXPECT_NEAR(clean.settled_n, kLimitN, 0.5);
  // The check out of the way: the limit holds what the sensor reads, the table feels the bias on
  // top.
  const PressRun unchecked = pressThroughTheLimit(PressRig(biasDown(), 1e3, 0.0));
  EXPECT_FALSE(unchecked.faulted) << unchecked.fault;
  EXPECT_GT(unchecked.settled_n, kLimitN + 0.8 * kBiasN) << "the bias did not defeat the limit?";
  const PressRun checked = pressThroughTheLimit(PressRig(biasDown(), 2.0, 0.0));
  EXPECT_TRUE(checked.faulted);
  // The probe is declared: the message names it against what the sensor carries, 8 N more.
  EXPECT_NE(checked.fault.find("wrist sensor: the declared tool (compensation.payload.mass_kg "
                               "0.06 kg)"),
            std::string::npos)
      << checked.fault;
  EXPECT_NE(checked.fault.find(": 8.0 N"), std::string::npos) << checked.fault;
  EXPECT_LT(checked.tcp_travel_m, 1e-3);
  EXPECT_LT(checked.peak_n, 0.5) << "the probe reached the table";
  std::printf(
      "20 N limit, sensor biased %.0f N: unbiased %.2f N, unchecked %.2f N, checked: "
      "FAULT, TCP %.3f mm (%s)\n",
      kBiasN, clean.settled_n, unchecked.settled_n, 1e3 * checked.tcp_travel_m,
      checked.fault.c_str());
}

TEST(SensorTrust, ABiasThatDriftsInWhilePressingDisagreesWithTheObserver) {
  // Without the comparison (the observer runs, the limit reads the sensor): the table feels the
  // drift on top of the limit.
  PressRig uncompared(Vector6d::Zero(), 2.0, 0.0);
  uncompared.config.observer.enabled = true;
  const PressRun drifted = pressThroughTheLimit(uncompared, kBiasN);
  EXPECT_FALSE(drifted.faulted) << drifted.fault;
  EXPECT_GT(drifted.settled_n, kLimitN + 0.8 * kBiasN);
  const PressRun compared = pressThroughTheLimit(PressRig(Vector6d::Zero(), 2.0, 3.0), kBiasN);
  EXPECT_TRUE(compared.faulted);
  EXPECT_NE(compared.fault.find("momentum observer"), std::string::npos) << compared.fault;
  EXPECT_LT(compared.peak_n, kLimitN + 5.0) << "the tolerance, the drift over 0.1 s and the lag";
  std::printf(
      "20 N limit, 8 N drifting in: %.2f N without the observer's comparison; with it "
      "FAULT at a peak of %.2f N (%s)\n",
      drifted.settled_n, compared.peak_n, compared.fault.c_str());
}

}  // namespace
}  // namespace comply::testing
