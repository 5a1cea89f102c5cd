#pragma once
// `comply experiment passivity`: what the gain stage (include/comply/pipeline/gain_guard.hpp)
// does against gains streamed adversarially, and what it costs a task that streams them
// normally. The FR3 with the Cartesian impedance plugin (config/sim/cartesian_impedance.yaml)
// in three conditions: none (no stage: the law reads the command), ramps (gain_ramps.enabled), tank
// (gain_ramps and passivity enabled); and, on request, tank_only (passivity alone). Four scenarios,
// the policy commanding at 500 Hz:
//
//   free_space_stiffness  reference 5 cm along base x; K = 100 N/m while the tool moves away from
//                         it, 3000 N/m while it returns; damping 5 N s/m (absolute)
//   free_space_frame      the same reference; K = diag(100, 3000, 3000) in a task frame that turns
//                         90 deg about z so that the stiff axis lies along the motion on return
//   wall_contact          a probe pressing on a wall, the reference 20 mm behind its face, K
//                         switched as in free_space_stiffness
//   normal_task           the reference 10 cm out and back in 2 s, K stepped from 500 to 2000 N/m
//                         at the far end, damping ratio 1
//
// Each run's energy (kinetic + the controller's springs, passivity/energy_meter.hpp) is traced
// every cycle; the table compares its start, peak and end, the tank's account, the contact and
// the tracking error.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "passivity/passivity_run.hpp"
#include "results_writer.hpp"

namespace comply::experiments {

struct PassivityOptions {
  std::filesystem::path out_dir = "out/passivity";
  /// Simulated seconds of each adversarial scenario (normal_task always takes its 3 s).
  double duration_s = 4.0;
  /// Ablation: the torque-rate limit per joint [N m/s]; unset: the controller file's (1000).
  std::optional<double> torque_rate_limit_nm_per_s;
  /// none, ramps, tank; tank_only (passivity without gain_ramps) for an ablation.
  std::vector<std::string> conditions{"none", "ramps", "tank"};
  bool pictures = true;
  std::ostream* progress = nullptr;
};

struct PassivityRow {
  std::string scenario;
  std::string condition;
  passivity::RunResult result;
};

/// Runs every scenario under every condition; writes <out>/<scenario>/<condition>.csv (every
/// cycle), <out>/wall_contact/wall.xml, <out>/results.json, <out>/table.md and, with pictures,
/// <out>/passivity.png.
std::vector<PassivityRow> runPassivity(const PassivityOptions& options);

/// The rows as table.md and results.json show them.
ResultsTable passivityTable(const std::vector<PassivityRow>& rows);

/// The command line: returns 0 (the energies are results, not checks).
int passivityCommand(const PassivityOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::experiments
