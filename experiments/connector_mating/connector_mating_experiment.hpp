#pragma once
// `comply experiment connector-mating`: a peg on the FR3 is inserted into a socket whose axis is
// tilted 1..6 deg from the peg's (angular misalignment); tight fit (0.25 mm radial clearance) with
// friction. Baseline: compliance fixed in the TCP frame (1000 N/m along the peg, 50 N/m
// laterally); task-aligned: the same gains in the socket's frame, updated with every command.
// Both get the same command: the TCP straight down the socket axis past the seat. The online
// conditions know nothing of the socket: the same gains in the Frenet-Serret frame of the
// measured TCP path, the reference advancing along its z at the same speed. A trial fails when
// the axial contact force exceeds a threshold before the peg is seated.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "results_writer.hpp"

namespace comply::experiments {

struct ConnectorMatingOptions {
  std::filesystem::path out_dir = "out/connector-mating";
  std::vector<double> offsets_deg{1, 2, 3, 4, 5, 6};
  /// tcp_fixed: gains in the commanded TCP frame; tcp_measured: in the measured TCP frame (the
  /// plugin's task_frame_reference: tcp); task_aligned: in the socket's frame; online_fsf: in the
  /// Frenet-Serret frame of the measured TCP path, the reference advancing along its z
  /// (orientation held); online_fsf_oriented: the same, the orientation following the frame.
  std::vector<std::string> conditions{"tcp_fixed", "task_aligned", "online_fsf",
                                      "online_fsf_oriented"};
  double axial_force_limit_n = 15.0;
  double rotational_stiffness_nm_per_rad = 10.0;  ///< during insertion, every condition
  /// Ablation: multiplies the plant's joint Coulomb friction (robot.yaml joint_dynamics).
  double plant_friction_scale = 1.0;
  /// Ablation: the posture spring during insertion [N m/rad] (MatingStream::overrideNullspace);
  /// unset: the controller's.
  std::optional<double> nullspace_stiffness_nm_per_rad;
  bool pictures = true;
  std::ostream* progress = nullptr;
};

struct ConnectorMatingRow {
  std::string condition;  ///< as in ConnectorMatingOptions::conditions
  double offset_deg = 0.0;
  bool seated = false;
  /// Why a trial that did not seat failed: "force_limit" (the axial force passed the limit) or
  /// "time_out" (still short of the seat when the run ended); empty when seated.
  std::string failure;
  double depth_mm = 0.0;  ///< deepest insertion along the socket axis (< 0: above the entrance)
  double peak_axial_force_n = 0.0;  ///< before seating (or over the trial)
  double seat_time_s = 0.0;         ///< NaN when not seated
  /// When the trial was decided (seated, force limit) or the run ended: the angle of the peg and
  /// of the stiff task axis to the socket's axis [deg].
  double peg_to_socket_deg = 0.0;
  double task_axis_to_socket_deg = 0.0;
};

/// Runs every condition at every offset; writes <out>/<condition>_<offset>deg/ (log, snapshots,
/// trace), <out>/peg.xml, <out>/results.json, <out>/table.md and, with pictures, the plot
/// <out>/connector_mating.png.
std::vector<ConnectorMatingRow> runConnectorMating(const ConnectorMatingOptions& options);

/// The rows as table.md and results.json show them.
ResultsTable connectorMatingTable(const std::vector<ConnectorMatingRow>& rows);

/// The command line: returns 0 (failed trials are results, not errors).
int connectorMatingCommand(const ConnectorMatingOptions& options, std::ostream& out,
                           std::ostream& err);

}  // namespace comply::experiments
