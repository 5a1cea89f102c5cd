#pragma once
// `comply experiment output-modes`: one Cartesian impedance law and one command schema on arms
// with torque, position and velocity drives (docs/output-modes.md). On the UR5e:
//
//   identification   a known wrench at the TCP along each axis of a turned task frame, the steady
//                    displacement measured on the plant: the rendered stiffness K = F / d per
//                    axis, against the commanded one;
//   contact          the probe brought down onto a rigid table, the reference 3 cm past its
//                    surface: peak and settled force, settling time, cycles without contact after
//                    the first touch (a bounce);
//   heavy tool       a 3 kg tool, a 5 cm step of the reference in admittance, with the tool
//                    declared (compensation.payload) and without: overshoot, crossings of the
//                    target, residual speed.
//
// The torque arm runs without robot.yaml's Coulomb friction in the identification: on a torque
// arm it leaves a dead band of +-f/K around the rest position, which the position and velocity
// servos remove with their integral action.

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "comply/core/actuator_command.hpp"
#include "results_writer.hpp"

namespace comply::experiments {

struct OutputModesOptions {
  std::filesystem::path out_dir = "out/output-modes";
  std::vector<OutputMode> modes = {OutputMode::kTorque, OutputMode::kPosition,
                                   OutputMode::kVelocity};
  bool pictures = true;
  std::ostream* progress = nullptr;
};

/// Task-frame stiffness commanded and rendered, translational [N/m] then rotational [N m/rad].
struct IdentifiedStiffness {
  std::array<double, 6> commanded{}, rendered{};
  [[nodiscard]] double worstErrorPercent() const;
};

struct TimeTrace {
  std::vector<double> time_s, value;
};

struct ContactResult {
  double peak_n = 0.0;
  double final_n = 0.0;
  double expected_n = 0.0;  ///< stiffness x how far the reference lies past the surface
  double settling_s = 0.0;  ///< after the first touch, until within 5 % of the final force
  int contact_losses = 0;   ///< cycles without contact after the first touch
  TimeTrace force;          ///< normal force [N] from the first touch [s]
};

struct ToolStepResult {
  double overshoot_mm = 0.0;
  int crossings = 0;                     ///< of the target, after the step
  double residual_speed_mm_per_s = 0.0;  ///< largest TCP speed in the last 0.5 s
  TimeTrace position;                    ///< TCP along the step minus the target [mm] from it [s]
};

/// The turned task frame of the identification (no axis is a base axis).
Eigen::Quaterniond identificationTaskFrame();

IdentifiedStiffness identifyStiffness(OutputMode mode);
ContactResult pressOnTable(OutputMode mode);
ToolStepResult heavyToolStep(bool declared);

struct OutputModesRow {
  OutputMode mode = OutputMode::kTorque;
  IdentifiedStiffness stiffness;
  ContactResult contact;
};

/// Runs every mode and the heavy tool both ways; writes <out>/results.json, <out>/table.md,
/// <out>/heavy_tool.md, <out>/contact_<mode>.csv, <out>/tool_<declared|undeclared>.csv and, with
/// pictures, <out>/output_modes.png.
std::vector<OutputModesRow> runOutputModes(const OutputModesOptions& options,
                                           std::array<ToolStepResult, 2>* tool = nullptr);

ResultsTable outputModesTable(const std::vector<OutputModesRow>& rows);
ResultsTable heavyToolTable(const std::array<ToolStepResult, 2>& tool);

/// The command line: returns 0 (the metrics are results, not checks).
int outputModesCommand(const OutputModesOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::experiments
