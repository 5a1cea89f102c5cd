#include "chunks/chunk_experiment.hpp"

#include <ostream>
#include <stdexcept>

#include "comply/core/number_text.hpp"
#include "comply/core/output_folder.hpp"

namespace comply::experiments {

chunks::Condition chunkConditionOf(const std::string& name) {
  for (const auto& [prefix, mode] : {std::pair{std::string("stepped_"), chunks::Mode::kStepped},
                                     std::pair{std::string("chunks_"), chunks::Mode::kChunks}}) {
    if (name.starts_with(prefix) && name.ends_with("hz")) {
      const std::optional<double> rate_hz =
          finiteNumber(name.substr(prefix.size(), name.size() - prefix.size() - 2));
      if (rate_hz && *rate_hz > 0.0 && *rate_hz <= 1000.0) {
        return {name, mode, *rate_hz};
      }
    }
  }
  throw std::invalid_argument("unknown chunk condition '" + name +
                              "' (stepped_<rate>hz or chunks_<rate>hz, e.g. chunks_10hz)");
}

std::vector<ChunkRow> runChunks(const ChunkOptions& options) {
  std::vector<chunks::Condition> conditions;
  for (const std::string& name : options.conditions) {
    conditions.push_back(chunkConditionOf(name));  // all refused before the first run
  }
  makeOutputFolder(options.out_dir);  // its parent must exist
  std::vector<ChunkRow> rows;
  for (const chunks::Condition& condition : conditions) {
    if (options.progress != nullptr) {
      *options.progress << "chunks: " << condition.name << "\n";
    }
    rows.push_back({condition, chunks::runCondition(condition, options.settings,
                                                    options.out_dir / (condition.name + ".csv"))});
  }
  writeResultsAndPlots(chunkTable(rows), options.out_dir, "plot_chunks.py", options.pictures,
                       options.progress);
  return rows;
}

ResultsTable chunkTable(const std::vector<ChunkRow>& rows) {
  ResultsTable table;
  table.columns = {
      Column("condition", "condition"),
      Column("rate_hz", "policy rate", "Hz", 0),
      Column("rmse_mm", "tracking RMSE", "mm", 2),
      Column("max_error_mm", "tracking max", "mm", 2),
      Column("max_torque_rate_nm_per_s", "max torque rate", "N m/s", 0),
      Column("rate_limit_hits", "rate-limit hits"),
      Column("max_reference_velocity_step_m_per_s", "max reference velocity step", "m/s", 4),
      Column("max_reference_acceleration_m_per_s2", "max reference acceleration", "m/s^2", 1),
      Column("max_reference_jerk_m_per_s3", "max reference jerk", "m/s^3", 0),
      Column("actions", "actions").jsonOnly(),
      Column("rejections", "rejections").jsonOnly(),
      Column("faults", "faults").jsonOnly(),
  };
  for (const ChunkRow& row : rows) {
    const chunks::RunResult& r = row.result;
    table.rows.push_back({row.condition.name, row.condition.rate_hz, r.rmse_mm, r.max_error_mm,
                          r.max_torque_rate_nm_per_s, static_cast<std::int64_t>(r.rate_limit_hits),
                          r.max_reference_velocity_step, r.max_reference_acceleration,
                          r.max_reference_jerk, static_cast<std::int64_t>(r.actions),
                          static_cast<std::int64_t>(r.rejections),
                          static_cast<std::int64_t>(r.faults)});
  }
  return table;
}

int chunksCommand(const ChunkOptions& options, std::ostream& out, std::ostream& err) {
  printResults(chunkTable(runChunks(withProgress(options, err))), options.out_dir,
               "results.json, table.md, chunks.png, a trace per condition", out);
  return 0;
}

}  // namespace comply::experiments
