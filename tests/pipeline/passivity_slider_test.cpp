// The energy tank against the classic counterexample, on a 1-DoF slider whose motion has a closed
// form: a mass on a spring whose stiffness is low while the mass moves away from the target and
// high while it comes back gains the factor K_high / K_low in energy every half period (the
// spring is stiffened at the turning point, where all the energy is in the spring, and softened
// where the error is zero and it costs nothing). The same pump by a task frame that turns an
// anisotropic stiffness. Without the tank the wrapper lets the energy grow by that factor; with
// it, spring + kinetic + tank energy never exceeds what was there at the start (no port does
// work here: no contact, a fixed target).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kMassKg = 2.0;
constexpr double kLowStiffness = 100.0;   // N/m
constexpr double kHighStiffness = 300.0;  // N/m
constexpr double kStart = 0.05;           // m from the target, at rest

/// A prismatic slider along x carrying 2 kg: M = 2 kg, J = e_x, no gravity along the joint.
class SliderRobot {
 public:
  SliderRobot()
      : folder_(std::filesystem::temp_directory_path() /
                ("comply_slider_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(folder_);
    std::ofstream(folder_ / "slider.urdf") << R"(<robot name="slider">
  <link name="base"/>
  <link name="carriage"><inertial><origin xyz="0 0 0"/><mass value="2.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="tool"/>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="-2" upper="2" velocity="10" effort="1000"/></joint>
  <joint name="to_tool" type="fixed"><parent link="carriage"/><child link="tool"/></joint>
</robot>)";
    std::ofstream(folder_ / "robot.yaml") << "name: slider\nurdf: slider.urdf\njoints: [slide]\n"
                                             "base_frame: base\nflange_frame: tool\n"
                                             "tcp_frame: tool\nhome: [0.0]\n";
  }
  ~SliderRobot() { std::filesystem::remove_all(folder_); }
  SliderRobot(const SliderRobot&) = delete;
  SliderRobot& operator=(const SliderRobot&) = delete;

  [[nodiscard]] WrapperConfig config(const std::string& plugin, const std::string& lines) const {
    return controllerConfig(
        plugin, folder_.string(),
        "soft_limits:\n  enabled: false\ntorque_rate_limit_nm_per_s: 1.0e9\n" + lines);
  }

 private:
  std::filesystem::path folder_;
};

std::string tankLines(bool tank, double damping, bool cartesian) {
  const std::string k = std::to_string(kHighStiffness);
  const std::string d = std::to_string(damping);
  // Ramps on with the tank (it needs them), so fast that a switch still lands in one cycle.
  std::string lines = std::string("gain_ramps:\n  enabled: ") + (tank ? "true" : "false") +
                      "\n  translational_stiffness_per_s: 1.0e9\n  joint_stiffness_per_s: 1.0e9\n"
                      "  task_frame_rad_per_s: 1.0e9\n"
                      "passivity:\n  enabled: " +
                      (tank ? "true" : "false") +
                      "\n  tank_initial_j: 1.0\n  tank_max_j: 2.0\ninitial:\n";
  if (!cartesian) {
    return lines + "  stiffness: " + k + "\n  damping: " + d + "\n";
  }
  return lines + "  stiffness_translational: [" + k + ", 0, 0, 0, " + k + ", 0, 0, 0, " + k +
         "]\n  stiffness_rotational: 10.0\n  damping_mode: absolute\n"
         "  damping_translational: " +
         d + "\n  damping_rotational: 1.0\n  nullspace_stiffness: 0.0\n  nullspace_damping: 0.0\n";
}

/// The mass under a torque held for one period, integrated exactly.
struct Slider {
  double position = kStart;
  double velocity = 0.0;
  void step(double force, double period_s) {
    const double acceleration = force / kMassKg;
    position += velocity * period_s + 0.5 * acceleration * period_s * period_s;
    velocity += acceleration * period_s;
  }
  [[nodiscard]] double kineticEnergy() const { return 0.5 * kMassKg * velocity * velocity; }
  [[nodiscard]] JointState state(double effort) const {
    JointState result = JointState::zero(1);
    result.position[0] = position;
    result.velocity[0] = velocity;
    result.effort[0] = effort;
    return result;
  }
};

/// The stiffness [N/m] along x the law reads this cycle.
double stiffnessInForce(const Controller& controller) {
  const CommandBus& bus = controller.lawBus();
  if (const auto* joint = std::get_if<comply_joint_command>(&bus)) {
    return joint->stiffness[0];
  }
  const auto& cartesian = std::get<comply_cartesian_command>(bus);
  const Eigen::Quaterniond frame(cartesian.task_frame[3], cartesian.task_frame[0],
                                 cartesian.task_frame[1], cartesian.task_frame[2]);
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> task(
      cartesian.stiffness_translational);
  const Eigen::Matrix3d rotation = frame.normalized().toRotationMatrix();
  return (rotation * task * rotation.transpose())(0, 0);
}

struct PumpResult {
  double initial_energy_j = 0.0;  ///< spring + kinetic + tanks
  double peak_energy_j = 0.0;     ///< the largest over the run
  double final_mechanical_j = 0.0;
  PassivitySnapshot tank;
  double largest_refusal_j = 0.0;  ///< the most the tank held back in one cycle
  int half_periods = 0;            ///< stiffenings at a turning point
};

enum class Pump { kStiffness, kTaskFrame };

/// Runs the pump for `seconds`: every cycle the "policy" sends the low stiffness while the mass
/// moves away from the target and the high one while it returns, either as a stiffness or by
/// turning a task frame with K = diag(low, high, high) by 90 degrees about z.
template <typename Command>
PumpResult runPump(Wrapper<Command>& wrapper, Pump pump, double seconds) {
  Slider slider;
  wrapper.activate(slider.state(0.0));
  // The target: the origin. Activation seeded it at the start position; move it.
  Command target = Command::zero(1);
  target.fields = CommandField::kPosition;
  target.stamp_s = 1e-3;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    target.position = Eigen::Vector3d::Zero();
  } else {
    target.position[0] = 0.0;
  }
  EXPECT_TRUE(wrapper.submit(target).accepted);

  const auto storage = [&wrapper, &slider] {
    const PassivitySnapshot tank = wrapper.controller().diagnostics().passivity();
    const double spring =
        0.5 * stiffnessInForce(wrapper.controller()) * slider.position * slider.position;
    return spring + slider.kineticEnergy() + tank.tank_energy_j + tank.nullspace_tank_energy_j;
  };
  PumpResult result;
  TorqueBuffer torque;
  bool returning = true;
  double stamp_s = 2e-3;
  const int cycles = static_cast<int>(seconds / kPeriod);
  for (int cycle = 0; cycle < cycles; ++cycle) {
    const bool now_returning = slider.position * slider.velocity <= 0.0;
    if (now_returning != returning || cycle == 0) {
      result.half_periods += now_returning && cycle > 0 ? 1 : 0;
      Command command = Command::zero(1);
      command.stamp_s = stamp_s += 1e-3;
      if constexpr (std::is_same_v<Command, CartesianCommand>) {
        if (pump == Pump::kStiffness) {
          command.fields = CommandField::kStiffness;
          command.stiffness_translational =
              Eigen::Vector3d::Constant(now_returning ? kHighStiffness : kLowStiffness)
                  .asDiagonal();
          command.stiffness_rotational = 10.0 * Eigen::Matrix3d::Identity();
        } else {
          // Low along the task x axis, high along y: the frame turned by 90 deg puts the high
          // stiffness on the base x axis, where the slider moves.
          command.fields = CommandField::kTaskFrame;
          command.task_frame =
              now_returning
                  ? Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))
                  : Eigen::Quaterniond::Identity();
        }
      } else {
        command.fields = CommandField::kStiffness;
        command.stiffness[0] = now_returning ? kHighStiffness : kLowStiffness;
      }
      EXPECT_TRUE(wrapper.submit(command).accepted) << "cycle " << cycle;
      returning = now_returning;
    }
    const double effort = torque.values[0] == TorqueBuffer::kUntouched ? 0.0 : torque.values[0];
    EXPECT_EQ(wrapper.update(slider.state(effort), kPeriod, torque.span().first(1)),
              CycleStatus::kOk);
    if (cycle == 0) {
      result.initial_energy_j = storage();
    }
    slider.step(torque.values[0], kPeriod);
    result.peak_energy_j = std::max(result.peak_energy_j, storage());
    result.largest_refusal_j = std::max(result.largest_refusal_j,
                                        wrapper.controller().diagnostics().passivity().refused_j);
  }
  result.final_mechanical_j =
      0.5 * stiffnessInForce(wrapper.controller()) * slider.position * slider.position +
      slider.kineticEnergy();
  result.tank = wrapper.controller().diagnostics().passivity();
  return result;
}

class PassivitySlider : public ::testing::Test {
 protected:
  SliderRobot robot;
};

// Without damping and without the tank, the energy multiplies by K_high / K_low = 3 every half
// period: the closed form the pump is known by. The wrapper passes the schedule unchanged.
void expectClosedFormGrowth(const PumpResult& result) {
  ASSERT_GE(result.half_periods, 3);
  const double start_j = 0.5 * kHighStiffness * kStart * kStart;
  const double closed_form_j = start_j * std::pow(kHighStiffness / kLowStiffness, 3);
  // After three stiffenings (at most one more half period has started since).
  EXPECT_GT(result.final_mechanical_j, 0.9 * closed_form_j);
  EXPECT_LT(result.final_mechanical_j, 1.1 * closed_form_j * kHighStiffness / kLowStiffness);
  EXPECT_FALSE(result.tank.enabled);
}

TEST_F(PassivitySlider, WithoutTheTankTheScheduleGrowsTheEnergyAsTheClosedFormSays) {
  JointWrapper joint(robot.config(kJointImpedancePlugin, tankLines(false, 0.0, false)));
  expectClosedFormGrowth(runPump(joint, Pump::kStiffness, 1.2));
  CartesianWrapper cartesian(robot.config(kCartesianImpedancePlugin, tankLines(false, 0.0, true)));
  expectClosedFormGrowth(runPump(cartesian, Pump::kStiffness, 1.2));
}

void expectBounded(const PumpResult& result) {
  // Sampling (torque from the state at the start of each period) is itself slightly active; the
  // damping covers it. The bound is the energy at the start, to a part in a thousand.
  EXPECT_LE(result.peak_energy_j, result.initial_energy_j * 1.001)
      << "started with " << result.initial_energy_j << " J";
  EXPECT_GT(result.tank.injected_j, 0.3) << "the tank paid for part of the schedule";
  EXPECT_GT(result.largest_refusal_j, 0.1) << "and refused the rest";
}

TEST_F(PassivitySlider, TheTankBoundsTheEnergyUnderTheStiffnessPumpJointWrapper) {
  JointWrapper without(robot.config(kJointImpedancePlugin, tankLines(false, 4.0, false)));
  const PumpResult grown = runPump(without, Pump::kStiffness, 3.0);
  EXPECT_GT(grown.final_mechanical_j, 5.0 * grown.initial_energy_j) << "damping beat the pump";

  JointWrapper wrapper(robot.config(kJointImpedancePlugin, tankLines(true, 4.0, false)));
  const PumpResult result = runPump(wrapper, Pump::kStiffness, 3.0);
  expectBounded(result);
}

TEST_F(PassivitySlider, TheTankBoundsTheEnergyUnderTheStiffnessPumpCartesianWrapper) {
  CartesianWrapper without(robot.config(kCartesianImpedancePlugin, tankLines(false, 4.0, true)));
  const PumpResult grown = runPump(without, Pump::kStiffness, 3.0);
  EXPECT_GT(grown.final_mechanical_j, 5.0 * grown.initial_energy_j);

  CartesianWrapper wrapper(robot.config(kCartesianImpedancePlugin, tankLines(true, 4.0, true)));
  const PumpResult result = runPump(wrapper, Pump::kStiffness, 3.0);
  expectBounded(result);
}

TEST_F(PassivitySlider, TheTankBoundsTheEnergyUnderTheTaskFramePump) {
  const std::string anisotropic =
      "  stiffness_translational: [100.0, 0, 0, 0, 300.0, 0, 0, 0, 300.0]\n";
  const auto lines = [&](bool tank) {
    std::string text = tankLines(tank, 4.0, true);
    const auto at = text.find("  stiffness_translational:");
    const auto end = text.find('\n', at);
    return text.replace(at, end - at + 1, anisotropic);
  };
  CartesianWrapper without(robot.config(kCartesianImpedancePlugin, lines(false)));
  const PumpResult grown = runPump(without, Pump::kTaskFrame, 3.0);
  EXPECT_GT(grown.final_mechanical_j, 5.0 * grown.initial_energy_j);

  CartesianWrapper wrapper(robot.config(kCartesianImpedancePlugin, lines(true)));
  const PumpResult result = runPump(wrapper, Pump::kTaskFrame, 3.0);
  expectBounded(result);
}

}  // namespace
}  // namespace comply::pipeline::test
