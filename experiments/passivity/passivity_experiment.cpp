#include "passivity/passivity_experiment.hpp"

#include <optional>
#include <ostream>
#include <stdexcept>

#include "comply/core/output_folder.hpp"

namespace comply::experiments {
namespace {

using passivity::Condition;
using passivity::Scenario;

template <typename Number>
Value valueOf(const std::optional<Number>& number) {
  return number ? Value{*number} : Value{};
}

}  // namespace

std::vector<PassivityRow> runPassivity(const PassivityOptions& options) {
  if (!(options.duration_s > 0.0) ||
      (options.torque_rate_limit_nm_per_s && !(*options.torque_rate_limit_nm_per_s > 0.0))) {
    throw std::runtime_error("passivity: the duration and the torque-rate limit must be > 0");
  }
  const passivity::RunSettings settings{options.duration_s, options.torque_rate_limit_nm_per_s};
  // Refuse an unknown condition before the first run rather than after the others.
  std::vector<Condition> conditions;
  for (const std::string& name : options.conditions) {
    conditions.push_back(passivity::conditionOf(name));
  }
  makeOutputFolder(options.out_dir);  // its parent must exist
  std::vector<PassivityRow> rows;
  for (const auto& [scenario, scenario_name] : passivity::kScenarios) {
    const std::filesystem::path folder = options.out_dir / scenario_name;
    std::filesystem::create_directories(folder);
    for (const Condition condition : conditions) {
      if (options.progress != nullptr) {
        *options.progress << "passivity: " << scenario_name << ", " << passivity::nameOf(condition)
                          << "\n";
      }
      rows.push_back({std::string(scenario_name), passivity::nameOf(condition),
                      passivity::runScenario(scenario, condition, settings,
                                             folder / (passivity::nameOf(condition) + ".csv"))});
    }
  }
  writeResultsAndPlots(passivityTable(rows), options.out_dir, "plot_passivity.py", options.pictures,
                       options.progress);
  return rows;
}

ResultsTable passivityTable(const std::vector<PassivityRow>& rows) {
  ResultsTable table;
  table.columns = {
      Column("scenario", "scenario"),
      Column("condition", "condition"),
      Column("initial_energy_j", "E start", "J", 3),
      Column("peak_energy_j", "E peak", "J", 3),
      Column("final_energy_j", "E end", "J", 3),
      Column("gain_work_j", "gain work", "J", 3),
      Column("tank_final_j", "tank end", "J", 3),
      Column("tank_injected_j", "tank paid", "J", 3),
      Column("tank_dissipated_j", "tank refilled", "J", 3).jsonOnly(),
      Column("refusing_share", "refusing", "share", 3),
      Column("stiffness_final_n_per_m", "K_x end", "N/m", 0),
      Column("peak_contact_force_n", "peak contact force", "N", 1),
      Column("peak_contact_force_mean_n", "peak contact force, 20 ms mean", "N", 1).jsonOnly(),
      Column("contact_losses", "contact losses"),
      Column("rebound_mm", "rebound", "mm", 1),
      Column("tracking_rms_mm", "tracking RMS", "mm", 2),
      Column("tracking_max_mm", "tracking max", "mm", 2),
      Column("rejections", "rejections").jsonOnly(),
      Column("faults", "faults").jsonOnly(),
      Column("rate_limit_hits", "rate limit hits").jsonOnly(),
      Column("effort_limit_hits", "effort limit hits").jsonOnly(),
  };
  for (const PassivityRow& row : rows) {
    const passivity::RunResult& result = row.result;
    table.rows.push_back({row.scenario,
                          row.condition,
                          result.initial_energy_j,
                          result.peak_energy_j,
                          result.final_energy_j,
                          result.gain_work_j,
                          valueOf(result.tank_final_j),
                          valueOf(result.tank_injected_j),
                          valueOf(result.tank_dissipated_j),
                          valueOf(result.refusing_share),
                          result.stiffness_final_n_per_m,
                          valueOf(result.peak_contact_force_n),
                          valueOf(result.peak_contact_force_mean_n),
                          valueOf(result.contact_losses),
                          valueOf(result.rebound_mm),
                          valueOf(result.tracking_rms_mm),
                          valueOf(result.tracking_max_mm),
                          static_cast<std::int64_t>(result.rejections),
                          static_cast<std::int64_t>(result.faults),
                          static_cast<std::int64_t>(result.rate_limit_hits),
                          static_cast<std::int64_t>(result.effort_limit_hits)});
  }
  return table;
}

int passivityCommand(const PassivityOptions& options, std::ostream& out, std::ostream& err) {
  printResults(
      passivityTable(runPassivity(withProgress(options, err))), options.out_dir,
      "results.json, table.md, passivity.png, one folder per scenario with a trace per condition",
      out);
  return 0;
}

}  // namespace comply::experiments
