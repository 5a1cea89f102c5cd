#pragma once
// One run of the passivity experiment: a scenario under a condition on the simulated FR3, its
// command stream at the policy rate, and what it is measured by, every control cycle: the
// arm's energy (EnergyMeter), the tank's account, the stiffness the law reads, the contact with
// the wall and the tracking error. The loop is the hosts' (hardware::ControlLoop on the plant's
// clock); the experiment observes it itself because it reads the controller's law bus and the
// plant's mass matrix, which the simulation log does not keep.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "comply/core/enum_names.hpp"

namespace comply::experiments::passivity {

enum class Scenario { kFreeSpaceStiffness, kFreeSpaceFrame, kWallContact, kNormalTask };
/// none: no gain stage (the law reads the command); ramps: gain_ramps.enabled; tank: gain_ramps
/// and passivity enabled; tank_only (an ablation): passivity without the ramps. Every other
/// option is config/sim/cartesian_impedance.yaml's.
enum class Condition { kNone, kRamps, kTank, kTankOnly };

/// Every scenario and every condition, by the names its folders, files, table and command line
/// give them. The experiment runs the scenarios in this order, which is the enum's.
inline constexpr EnumNames<Scenario, 4> kScenarios{
    {{Scenario::kFreeSpaceStiffness, "free_space_stiffness"},
     {Scenario::kFreeSpaceFrame, "free_space_frame"},
     {Scenario::kWallContact, "wall_contact"},
     {Scenario::kNormalTask, "normal_task"}}};
inline constexpr EnumNames<Condition, 4> kConditions{{{Condition::kNone, "none"},
                                                      {Condition::kRamps, "ramps"},
                                                      {Condition::kTank, "tank"},
                                                      {Condition::kTankOnly, "tank_only"}}};

std::string nameOf(Scenario scenario);
std::string nameOf(Condition condition);
/// The condition called `name`; throws std::invalid_argument on anything else.
Condition conditionOf(const std::string& name);

/// Commands a policy sends: every 2 ms (500 Hz), fast enough to switch within a few
/// milliseconds of each turning point, as a learned policy or a teleoperator might.
inline constexpr double kPolicyPeriodS = 0.002;

struct RunResult {
  double initial_energy_j = 0.0;  ///< after the first cycle, the first command in force
  double peak_energy_j = 0.0;
  double final_energy_j = 0.0;
  /// Net energy the changes of stiffness and task frame put into the springs: each cycle, the
  /// springs of the law's new gains minus those of its previous gains, at the same pose.
  double gain_work_j = 0.0;
  // The tank's account at the end (PassivitySnapshot); with the tank off, none.
  std::optional<double> tank_final_j;
  std::optional<double> tank_injected_j;
  std::optional<double> tank_dissipated_j;
  /// Share of cycles in which the tank held back part of a change.
  std::optional<double> refusing_share;
  double stiffness_final_n_per_m = 0.0;  ///< the law's stiffness along base x at the end
  // wall_contact: peak contact force on the tool (one cycle's, as MuJoCo reports it and over a
  // 20 ms mean), times contact was lost after the first touch, largest rebound from the wall.
  std::optional<double> peak_contact_force_n;
  std::optional<double> peak_contact_force_mean_n;
  std::optional<std::int64_t> contact_losses;
  std::optional<double> rebound_mm;
  // normal_task: TCP against the reference over the run.
  std::optional<double> tracking_rms_mm;
  std::optional<double> tracking_max_mm;
  std::uint64_t rejections = 0;
  std::uint64_t faults = 0;
  std::uint64_t rate_limit_hits = 0;    ///< joint-cycles clipped by the torque-rate limit
  std::uint64_t effort_limit_hits = 0;  ///< joint-cycles clipped at the effort limit
};

/// What the runs of one experiment share.
struct RunSettings {
  double duration_s = 4.0;  ///< simulated seconds of an adversarial scenario
  /// Ablation: the torque-rate limit per joint [N m/s]; unset: the controller file's.
  std::optional<double> torque_rate_limit_nm_per_s;
};

/// Runs `scenario` under `condition` (normal_task for its own length); writes every cycle to
/// `trace_file` (CSV) and the wall's fragment, if any, next to it.
RunResult runScenario(Scenario scenario, Condition condition, const RunSettings& settings,
                      const std::filesystem::path& trace_file);

}  // namespace comply::experiments::passivity
