#include "output_modes/output_modes_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <ostream>
#include <stdexcept>
#include <string>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/plot_script.hpp"
#include "output_modes/output_mode_rig.hpp"
#include "source_dir.hpp"

namespace comply::experiments {
namespace {

const std::string kRobot = "ur5e";

// Identification: task-frame stiffness, pushes, and how long each settles.
const std::array<double, 6> kIdentifiedStiffness = {800.0, 1500.0, 2500.0, 40.0, 60.0, 90.0};
constexpr double kPushForceN = 15.0;
constexpr double kPushTorqueNm = 1.5;
constexpr int kSettleCycles = 1500;
constexpr int kPushCycles = 2500;

// Contact: the probe (examples/sim/probe_tool.xml, ball 10 cm out) over the table
// (examples/sim/table.xml, top at 0.30 m).
constexpr double kPressStiffness = 1000.0;  // N/m along base z
constexpr double kPenetrationM = 0.03;
constexpr double kContactZ = 0.41;  // TCP height at the first touch
constexpr int kPressCycles = 7000;

// Heavy tool (examples/sim/payload_3kg.xml): 3 kg at 5 cm, a 10 g ball at 10 cm.
constexpr double kToolMassKg = 3.01;
constexpr double kToolComM = (3.0 * 0.05 + 0.01 * 0.1) / 3.01;
constexpr double kStepM = 0.05;
constexpr int kStepCycle = 500;
constexpr int kToolCycles = 4000;

void require(bool ok, const std::string& what) {
  if (!ok) {
    throw std::runtime_error("comply experiment output-modes: " + what);
  }
}

/// One cycle of `rig`, which must leave the controller active; the FAULT's reason read after the
/// cycle (as an argument beside the cycle, it could be read before it).
template <typename Rig>
void requireCycle(Rig& rig, const std::string& what) {
  if (!rig.cycle()) {
    require(false, what + ": " + rig.wrapper.diagnostics().last_fault);
  }
}

/// How far the TCP moved from `reference` to `now`, in the task frame: position [m], rotation
/// vector [rad].
Vector6d displacementInTask(const Eigen::Isometry3d& reference, const Eigen::Isometry3d& now) {
  const Eigen::Matrix3d task = identificationTaskFrame().toRotationMatrix();
  Vector6d moved;
  moved.head<3>() = task.transpose() * (now.translation() - reference.translation());
  const Eigen::AngleAxisd turned(now.linear() * reference.linear().transpose());
  moved.tail<3>() = task.transpose() * (turned.angle() * turned.axis());
  return moved;
}

/// A smooth straight line from `from` to `to` over cycles [start, end].
CartesianCommand along(int cycle, int start, int end, const Eigen::Vector3d& from,
                       const Eigen::Vector3d& to, const Eigen::Quaterniond& orientation, int dof) {
  const double s = std::clamp(static_cast<double>(cycle - start) / (end - start), 0.0, 1.0);
  CartesianCommand target = CartesianCommand::zero(dof);
  target.fields = CommandField::kPosition;
  target.stamp_s = cycle * kRigPeriodS;
  target.position = from + (3.0 * s * s - 2.0 * s * s * s) * (to - from);
  target.orientation = orientation;
  return target;
}

void writeTrace(const TimeTrace& trace, const char* value_name, const std::filesystem::path& file) {
  std::ofstream out(file);
  require(static_cast<bool>(out), "cannot write " + file.string());
  out << "time_s," << value_name << "\n";
  for (std::size_t i = 0; i < trace.time_s.size(); ++i) {
    out << trace.time_s[i] << "," << trace.value[i] << "\n";
  }
}

}  // namespace

pipeline::WrapperConfig outputModeConfig(const std::string& robot, OutputMode mode,
                                         bool cartesian) {
  pipeline::WrapperConfig config =
      host::simControllerConfig(robot, "",
                                sourcePath(cartesian ? "config/sim/cartesian_impedance.yaml"
                                                     : "config/sim/joint_impedance.yaml")
                                    .string());
  config.output.mode = mode;
  return config;
}

sim::PlantOptions plantOf(OutputMode actuation) {
  sim::PlantOptions options;
  options.actuation = actuation;
  return options;
}

double IdentifiedStiffness::worstErrorPercent() const {
  double worst = 0.0;
  for (std::size_t axis = 0; axis < 6; ++axis) {
    worst = std::max(worst, 100.0 * std::abs(rendered[axis] / commanded[axis] - 1.0));
  }
  return worst;
}

Eigen::Quaterniond identificationTaskFrame() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
}

IdentifiedStiffness identifyStiffness(OutputMode mode) {
  pipeline::WrapperConfig config = outputModeConfig(kRobot, mode);
  config.initial_cartesian.task_frame = identificationTaskFrame();
  config.initial_cartesian.stiffness_translational =
      Eigen::Vector3d(kIdentifiedStiffness[0], kIdentifiedStiffness[1], kIdentifiedStiffness[2])
          .asDiagonal();
  config.initial_cartesian.stiffness_rotational =
      Eigen::Vector3d(kIdentifiedStiffness[3], kIdentifiedStiffness[4], kIdentifiedStiffness[5])
          .asDiagonal();
  sim::PlantOptions plant = plantOf(mode);
  plant.friction_scale = mode == OutputMode::kTorque ? 0.0 : 1.0;
  OutputModeRig<> rig(config, plant);
  const auto cycles = [&](int count, const char* phase) {
    for (int cycle = 0; cycle < count; ++cycle) {
      requireCycle(rig, std::string(toString(mode)) + ", " + phase);
    }
  };
  cycles(kSettleCycles, "settling");
  const Eigen::Matrix3d task = identificationTaskFrame().toRotationMatrix();
  IdentifiedStiffness found;
  found.commanded = kIdentifiedStiffness;
  for (int axis = 0; axis < 6; ++axis) {
    const Eigen::Isometry3d before = rig.plant.tcpPose();
    const bool force = axis < 3;
    const double push = force ? kPushForceN : kPushTorqueNm;
    Vector6d wrench = Vector6d::Zero();
    wrench.segment<3>(force ? 0 : 3) = task.col(axis % 3) * push;
    rig.plant.setExternalWrench(wrench);
    cycles(kPushCycles, "pushed");
    found.rendered[static_cast<std::size_t>(axis)] =
        push / displacementInTask(before, rig.plant.tcpPose())[axis];
    rig.plant.setExternalWrench(Vector6d::Zero());
    cycles(kPushCycles, "released");
  }
  return found;
}

ContactResult pressOnTable(OutputMode mode) {
  pipeline::WrapperConfig config = outputModeConfig(kRobot, mode);
  config.initial_cartesian.stiffness_translational =
      Eigen::Vector3d(2000.0, 2000.0, kPressStiffness).asDiagonal();
  sim::PlantOptions options = plantOf(mode);
  options.substeps = 2;
  options.scene.tool = sourcePath("examples/sim/probe_tool.xml");
  options.scene.objects = {sourcePath("examples/sim/table.xml")};
  OutputModeRig<> rig(config, options);
  const int dof = rig.wrapper.dof();
  const MeasuredPose home = rig.wrapper.measuredPose();
  // Home's orientation turned the least so that TCP z (the probe) points down.
  const Eigen::Quaterniond down =
      Eigen::Quaterniond::FromTwoVectors(home.tcp_orientation * Eigen::Vector3d::UnitZ(),
                                         -Eigen::Vector3d::UnitZ()) *
      home.tcp_orientation;
  const Eigen::Vector3d above(0.45, 0.1, kContactZ + 0.02);
  const Eigen::Vector3d pressed(0.45, 0.1, kContactZ - kPenetrationM);
  ContactResult result;
  result.expected_n = kPressStiffness * kPenetrationM;
  int first_touch = -1;
  for (int cycle = 0; cycle < kPressCycles; ++cycle) {
    const CartesianCommand target = cycle < 3000
                                        ? along(cycle, 0, 2500, home.tcp_position, above, down, dof)
                                        : along(cycle, 3000, 4000, above, pressed, down, dof);
    const pipeline::Verdict verdict = rig.wrapper.submit(target);
    require(verdict.accepted, "contact, " + std::string(toString(mode)) + ": " + verdict.message);
    requireCycle(rig, "contact, " + std::string(toString(mode)));
    const double normal = rig.plant.toolContactWrench()[2];  // the table pushes up
    if (first_touch < 0 && normal > 0.0) {
      first_touch = cycle;
    }
    if (first_touch >= 0) {
      result.force.time_s.push_back((cycle - first_touch) * kRigPeriodS);
      result.force.value.push_back(normal);
      result.contact_losses += normal <= 0.0 ? 1 : 0;
      result.peak_n = std::max(result.peak_n, normal);
    }
  }
  require(result.force.value.size() > 500, "the probe never reached the table");
  const std::vector<double>& force = result.force.value;
  for (std::size_t i = force.size() - 500; i < force.size(); ++i) {
    result.final_n += force[i] / 500.0;
  }
  for (std::size_t i = force.size(); i-- > 0;) {
    if (std::abs(force[i] - result.final_n) > 0.05 * result.final_n) {
      result.settling_s = result.force.time_s[i] + kRigPeriodS;
      break;
    }
  }
  return result;
}

ToolStepResult heavyToolStep(bool declared) {
  pipeline::WrapperConfig config = outputModeConfig(kRobot, OutputMode::kPosition);
  config.payload_compensation = declared;
  config.payload.mass_kg = kToolMassKg;
  config.payload.com_in_tip = Eigen::Vector3d(0.0, 0.0, kToolComM);
  if (!declared) {
    // The wrist sensor's rest check refuses an undeclared 3 kg tool at activation (it reads as a
    // 30 N push); the run shows what declaring the tool, and the check, guard against.
    config.wrench_sensor.rest_force_tolerance_n = 1e3;
  }
  sim::PlantOptions options = plantOf(OutputMode::kPosition);
  options.scene.tool = sourcePath("examples/sim/payload_3kg.xml");
  OutputModeRig<> rig(config, options);
  const MeasuredPose home = rig.wrapper.measuredPose();
  CartesianCommand step = CartesianCommand::zero(rig.wrapper.dof());
  step.fields = CommandField::kPosition;
  step.stamp_s = kStepCycle * kRigPeriodS;
  step.position = home.tcp_position + Eigen::Vector3d(0.0, kStepM, 0.0);
  step.orientation = home.tcp_orientation;
  ToolStepResult result;
  double last_error = -1.0;
  Eigen::Vector3d last_position = rig.plant.tcpPose().translation();
  for (int cycle = 0; cycle < kToolCycles; ++cycle) {
    if (cycle == kStepCycle) {
      const pipeline::Verdict verdict = rig.wrapper.submit(step);
      require(verdict.accepted, "heavy tool: " + verdict.message);
    }
    requireCycle(rig, "heavy tool");
    const Eigen::Vector3d position = rig.plant.tcpPose().translation();
    if (cycle >= kStepCycle) {
      const double error = position.y() - step.position.y();  // negative until it arrives
      result.position.time_s.push_back((cycle - kStepCycle) * kRigPeriodS);
      result.position.value.push_back(error * 1e3);
      result.overshoot_mm = std::max(result.overshoot_mm, error * 1e3);
      result.crossings += cycle > kStepCycle && (error > 0.0) != (last_error > 0.0) ? 1 : 0;
      last_error = error;
    }
    if (cycle >= kToolCycles - 500) {
      result.residual_speed_mm_per_s = std::max(
          result.residual_speed_mm_per_s, (position - last_position).norm() / kRigPeriodS * 1e3);
    }
    last_position = position;
  }
  return result;
}

std::vector<OutputModesRow> runOutputModes(const OutputModesOptions& options,
                                           std::array<ToolStepResult, 2>* tool) {
  makeOutputFolder(options.out_dir);  // its parent must exist
  std::ostream& progress = options.progress != nullptr ? *options.progress : std::cerr;
  std::vector<OutputModesRow> rows;
  for (const OutputMode mode : options.modes) {
    const std::string name(toString(mode));
    progress << "output-modes: " << name << " drives: identification, contact\n";
    OutputModesRow row{mode, identifyStiffness(mode), pressOnTable(mode)};
    writeTrace(row.contact.force, "force_n", options.out_dir / ("contact_" + name + ".csv"));
    rows.push_back(row);
  }
  progress << "output-modes: a 3 kg tool, declared and not\n";
  const std::array<ToolStepResult, 2> steps = {heavyToolStep(true), heavyToolStep(false)};
  writeTrace(steps[0].position, "error_mm", options.out_dir / "tool_declared.csv");
  writeTrace(steps[1].position, "error_mm", options.out_dir / "tool_undeclared.csv");
  writeResults(outputModesTable(rows), options.out_dir);
  std::ofstream tool_table(options.out_dir / "heavy_tool.md");
  writeMarkdownTable(heavyToolTable(steps), tool_table);
  if (options.pictures) {
    host::runPlotScript("plot_output_modes.py", {options.out_dir.string()}, progress);
  }
  if (tool != nullptr) {
    *tool = steps;
  }
  return rows;
}

ResultsTable outputModesTable(const std::vector<OutputModesRow>& rows) {
  ResultsTable table;
  table.columns = {Column("drives", "drives")};
  const char* axes[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int axis = 0; axis < 6; ++axis) {
    const bool force = axis < 3;
    table.columns.emplace_back(Column(std::string("k_") + axes[axis],
                                      std::string("K ") + axes[axis], force ? "N/m" : "N m/rad",
                                      force ? 0 : 1));
  }
  table.columns.emplace_back(Column("worst_k_error_percent", "worst K error", "%", 2));
  table.columns.emplace_back(Column("peak_force_n", "peak force", "N", 1));
  table.columns.emplace_back(Column("final_force_n", "settled force", "N", 1));
  table.columns.emplace_back(Column("expected_force_n", "K x depth", "N", 1).jsonOnly());
  table.columns.emplace_back(Column("settling_s", "settling", "s", 3));
  table.columns.emplace_back(Column("contact_losses", "cycles off the table"));
  for (const OutputModesRow& row : rows) {
    std::vector<Value> values{std::string(toString(row.mode))};
    for (const double k : row.stiffness.rendered) {
      values.emplace_back(k);
    }
    values.insert(values.end(), {row.stiffness.worstErrorPercent(), row.contact.peak_n,
                                 row.contact.final_n, row.contact.expected_n,
                                 row.contact.settling_s, std::int64_t{row.contact.contact_losses}});
    table.rows.push_back(values);
  }
  return table;
}

ResultsTable heavyToolTable(const std::array<ToolStepResult, 2>& tool) {
  ResultsTable table;
  table.columns = {Column("tool", "3 kg tool"), Column("overshoot_mm", "overshoot", "mm", 2),
                   Column("crossings", "crossings of the target"),
                   Column("residual_speed_mm_per_s", "speed in the last 0.5 s", "mm/s", 2)};
  const char* names[] = {"declared (compensation.payload)", "not declared"};
  for (std::size_t i = 0; i < 2; ++i) {
    table.rows.push_back({std::string(names[i]), tool[i].overshoot_mm,
                          std::int64_t{tool[i].crossings}, tool[i].residual_speed_mm_per_s});
  }
  return table;
}

int outputModesCommand(const OutputModesOptions& options, std::ostream& out, std::ostream& err) {
  OutputModesOptions run = options;
  run.progress = &err;
  std::array<ToolStepResult, 2> tool;
  const std::vector<OutputModesRow> rows = runOutputModes(run, &tool);
  out << "UR5e, commanded K: 800 / 1500 / 2500 N/m, 40 / 60 / 90 N m/rad in a turned task frame; "
         "contact: K_z 1000 N/m, 3 cm past the table\n";
  writeMarkdownTable(outputModesTable(rows), out);
  out << "\n";
  writeMarkdownTable(heavyToolTable(tool), out);
  out << "results in " << std::filesystem::absolute(options.out_dir).string()
      << " (results.json, table.md, heavy_tool.md, traces, output_modes.png)\n";
  return 0;
}

}  // namespace comply::experiments
