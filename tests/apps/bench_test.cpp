// `comply bench` pieces that decide what the figures mean: the merge over processes (medians and
// the spread), the robot list, and the synthetic chain that shows the growth with DOF.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench_command.hpp"
#include "comply/host/synthetic_chain.hpp"
#include "comply/model/robot_description.hpp"

namespace comply::app {
namespace {

BenchRow row(const std::string& stage, double p50, double mean) {
  BenchRow result;
  result.robot = "fr3";
  result.dof = 7;
  result.wrapper = "cartesian";
  result.plugin = "cartesian_impedance";
  result.stage = stage;
  result.timing = {mean, 0.1, p50, 2.0 * p50, 10.0 * p50, 5.0 * p50};
  return result;
}

TEST(BenchMerge, ReportsTheMedianOfEachStatisticAndTheSpreadOfTheMedians) {
  const std::vector<std::vector<BenchRow>> runs = {
      {row("plugin_step", 1.0, 1.1), row("full_cycle", 2.0, 2.2)},
      {row("plugin_step", 1.8, 1.2), row("full_cycle", 2.1, 9.0)},  // a preempted process
      {row("plugin_step", 1.1, 1.3), row("full_cycle", 2.4, 2.5)}};
  const std::vector<BenchRow> merged = mergeBenchRuns(runs);
  ASSERT_EQ(merged.size(), 2U);
  EXPECT_DOUBLE_EQ(merged[0].timing.p50_us, 1.1);
  EXPECT_DOUBLE_EQ(merged[0].p50_min_us, 1.0);
  EXPECT_DOUBLE_EQ(merged[0].p50_max_us, 1.8);
  EXPECT_DOUBLE_EQ(merged[1].timing.mean_us, 2.5);  // the outlier's mean does not carry
  EXPECT_DOUBLE_EQ(merged[1].timing.p99_us, 2.0 * 2.1);
  EXPECT_DOUBLE_EQ(merged[1].timing.p999_us, 5.0 * 2.1);
  EXPECT_EQ(merged[1].processes, 3);
}

TEST(TimingSummary, PercentilesByNearestRankUpToTheTail) {
  std::vector<double> samples(1000);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i] = static_cast<double>(1000 - i);  // 1000 .. 1, unsorted on purpose
  }
  const host::TimingSummary summary = host::summarize(samples);
  EXPECT_DOUBLE_EQ(summary.p50_us, 500.0);
  EXPECT_DOUBLE_EQ(summary.p99_us, 990.0);
  EXPECT_DOUBLE_EQ(summary.p999_us, 999.0);
  EXPECT_DOUBLE_EQ(summary.max_us, 1000.0);
}

TEST(BenchMerge, RefusesProcessesThatReportDifferentRows) {
  EXPECT_THROW(mergeBenchRuns({{row("plugin_step", 1.0, 1.0)}, {row("full_cycle", 1.0, 1.0)}}),
               std::runtime_error);
}

TEST(BenchMerge, RowsSurviveTheJsonBetweenProcesses) {
  BenchOptions options;
  const std::vector<BenchRow> rows = {row("full_cycle", 1.25, 1.5)};
  const std::vector<BenchRow> back = benchRowsFromJson(benchRowsToJson(options, rows));
  ASSERT_EQ(back.size(), 1U);
  EXPECT_EQ(back[0].stage, "full_cycle");
  EXPECT_EQ(back[0].dof, 7);
  EXPECT_DOUBLE_EQ(back[0].timing.p50_us, 1.25);
  EXPECT_DOUBLE_EQ(back[0].timing.mean_us, 1.5);
  EXPECT_DOUBLE_EQ(back[0].timing.p999_us, 5.0 * 1.25);
}

// The reference figures of other implementations were measured on the development machine, not on
// the one that runs the bench: both outputs say where and when, and the page that holds them.
TEST(BenchReference, FiguresNameTheMachineAndDateTheyWereMeasuredOn) {
  BenchOptions options;
  const std::vector<BenchRow> rows = {row("full_cycle", 1.25, 1.5)};
  std::ostringstream table;
  printBench(options, rows, table);
  EXPECT_EQ(table.str().find("on this machine"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("\nfor reference (fr3, measured on the development machine, a 2 vCPU "
                             "VM with an AMD EPYC (AVX-512) and GCC 12, on 2026-11-22; "
                             "docs/timing.md): published implementation 7.2 us (step) / 8.3 us "
                             "(step + wrapper); an equivalent Pinocchio bundle 1.8-2.5 us\n"),
            std::string::npos)
      << table.str();

  options.json = true;
  std::ostringstream json;
  printBench(options, rows, json);
  const nlohmann::json reference = nlohmann::json::parse(json.str()).at("reference");
  EXPECT_EQ(reference.at("measured_on"),
            "the development machine, a 2 vCPU VM with an AMD EPYC (AVX-512) and GCC 12");
  EXPECT_EQ(reference.at("date"), "2026-11-22");
  EXPECT_EQ(reference.at("source"), "docs/timing.md");
  EXPECT_EQ(reference.at("published_step_us"), 7.2);
}

TEST(BenchRobots, AllIsEveryRobotAndTheTwelveJointChain) {
  std::vector<std::string> all = model::availableRobots();
  ASSERT_GE(all.size(), 4U) << "robots/ holds fr3, iiwa14, rizon4s and ur5e";
  all.push_back("chain12");
  EXPECT_EQ(benchRobots("all"), all);
  EXPECT_EQ(benchRobots("fr3,ur5e"), (std::vector<std::string>{"fr3", "ur5e"}));
  EXPECT_THROW(benchRobots(","), std::runtime_error);
}

TEST(SyntheticChain, NamesParseOnlyWithinTheCapacity) {
  EXPECT_EQ(host::syntheticChainDof("chain12"), 12);
  EXPECT_EQ(host::syntheticChainDof("chain3"), 3);
  EXPECT_EQ(host::syntheticChainDof("chain13"), 0);
  EXPECT_EQ(host::syntheticChainDof("chain"), 0);
  EXPECT_EQ(host::syntheticChainDof("fr3"), 0);
}

TEST(SyntheticChain, TwelveJointsLoadAndRunEveryWrapperWithoutAFault) {
  const std::filesystem::path folder = host::writeSyntheticChain(
      12, std::filesystem::temp_directory_path() / "comply-bench-test-chain");
  const model::RobotDescription robot = model::loadRobotDescription(folder.string());
  EXPECT_EQ(robot.loadModel().dof(), 12);
  BenchOptions options;
  options.robot = folder.string();
  options.iterations = 200;
  options.warmup = 10;
  std::ostringstream log;
  const std::vector<BenchRow> rows = runBench(options, log);  // throws on a fault
  // joint, cartesian, cartesian_abs, cartesian_tank, cartesian_observer, cartesian_force,
  // cartesian_walls, cartesian_reflex, cartesian_contact, cartesian_safety, cartesian_chunk,
  // cartesian_joint_pd, cartesian_admittance: step and cycle; cartesian_recorded also the push, the push into a full
  // lane and the state sample.
  ASSERT_EQ(rows.size(), 31U);
  int recording_stages = 0;
  for (const BenchRow& bench_row : rows) {
    EXPECT_EQ(bench_row.dof, 12);
    EXPECT_GT(bench_row.timing.p50_us, 0.0);
    recording_stages += bench_row.stage == "record_push" || bench_row.stage == "record_push_full" ||
                                bench_row.stage == "state_sample"
                            ? 1
                            : 0;
  }
  EXPECT_EQ(recording_stages, 3);
  EXPECT_EQ(log.str().find("dropped"), std::string::npos) << log.str();  // nothing lost
  std::filesystem::remove_all(folder);
}

TEST(Bench, PacedRowsRunTheCycleOnTheWallClock) {
  BenchOptions options;
  options.iterations = 200;
  options.warmup = 10;
  options.paced_hz = 1000.0;
  std::ostringstream log;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<BenchRow> rows = runBench(options, log);
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Fourteen wrappers: step, back to back, paced asleep, paced spinning, paced warmed ahead; the
  // recorded one also its three recording stages.
  ASSERT_EQ(rows.size(), 73U);
  int paced = 0;
  int spinning = 0;
  int warmed = 0;
  for (const BenchRow& bench_row : rows) {
    paced += bench_row.stage == "paced_cycle" ? 1 : 0;
    spinning += bench_row.stage == "paced_spin" ? 1 : 0;
    warmed += bench_row.stage == "paced_warm" ? 1 : 0;
    EXPECT_GT(bench_row.timing.p50_us, 0.0) << bench_row.wrapper << " " << bench_row.stage;
  }
  EXPECT_EQ(paced, 14);
  EXPECT_EQ(spinning, 14);
  EXPECT_EQ(warmed, 14);
  // Three times 210 cycles per wrapper at 1 kHz on the wall clock: paced, not free-running.
  EXPECT_GT(elapsed_s, 42 * 0.2);
}

}  // namespace
}  // namespace comply::app
