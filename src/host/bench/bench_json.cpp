// A bench run's rows as JSON and back (see cycle_bench.hpp): the worker processes' output and
// `comply bench --json`.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "comply/host/cycle_bench.hpp"

namespace comply::host {

std::string benchRowsToJson(const BenchOptions& options, const std::vector<BenchRow>& rows) {
  nlohmann::json document;
  document["iterations"] = options.iterations;
  document["rows"] = nlohmann::json::array();
  for (const BenchRow& row : rows) {
    document["rows"].push_back({{"robot", row.robot},
                                {"dof", row.dof},
                                {"wrapper", row.wrapper},
                                {"plugin", row.plugin},
                                {"stage", row.stage},
                                {"mean_us", row.timing.mean_us},
                                {"sd_us", row.timing.sd_us},
                                {"p50_us", row.timing.p50_us},
                                {"p99_us", row.timing.p99_us},
                                {"p999_us", row.timing.p999_us},
                                {"max_us", row.timing.max_us},
                                {"p50_min_us", row.p50_min_us},
                                {"p50_max_us", row.p50_max_us},
                                {"processes", row.processes}});
  }
  document["reference"] = {
      {"published_step_us", kReferenceFigures.published_step_us},
      {"published_step_and_wrapper_us", kReferenceFigures.published_cycle_us},
      {"pinocchio_bundle_us",
       {kReferenceFigures.pinocchio_low_us, kReferenceFigures.pinocchio_high_us}},
      {"measured_on", kReferenceFigures.machine},
      {"date", kReferenceFigures.date},
      {"source", kReferenceFigures.source}};
  return document.dump(2);
}

std::vector<BenchRow> benchRowsFromJson(const std::string& text) {
  const nlohmann::json document = nlohmann::json::parse(text);
  std::vector<BenchRow> rows;
  for (const nlohmann::json& item : document.at("rows")) {
    BenchRow row;
    row.robot = item.at("robot").get<std::string>();
    row.dof = item.at("dof").get<int>();
    row.wrapper = item.at("wrapper").get<std::string>();
    row.plugin = item.at("plugin").get<std::string>();
    row.stage = item.at("stage").get<std::string>();
    row.timing = {item.at("mean_us").get<double>(), item.at("sd_us").get<double>(),
                  item.at("p50_us").get<double>(),  item.at("p99_us").get<double>(),
                  item.at("max_us").get<double>(),  item.value("p999_us", 0.0)};
    row.p50_min_us = item.value("p50_min_us", row.timing.p50_us);
    row.p50_max_us = item.value("p50_max_us", row.timing.p50_us);
    row.processes = item.value("processes", 1);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace comply::host
