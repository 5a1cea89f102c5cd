#pragma once
// `comply experiment chunks`: a circle tracked from a policy's actions, stepped setpoints against
// timed chunks (docs/chunks.md). The FR3 with the Cartesian impedance plugin
// (config/sim/cartesian_impedance.yaml) follows a 5 cm circle at 0.16 m/s commanded by a scripted
// policy that acts on an observation and is heard 40 ms later, each action 1 mm off on its own:
//
//   stepped_15hz   one target per step, 1/15 s ahead, held until the next (DROID's stepping)
//   chunks_10hz    16 waypoints 1/15 s apart every 0.1 s, each chunk taking over from the last
//   chunks_15hz    the same every 1/15 s
//   chunks_30hz    the same every 1/30 s
//
// The table compares tracking (RMSE and max against the circle), the torque rate and the
// torque-rate limiter's hits, and the smoothness of the reference (its largest velocity step per
// cycle, acceleration and jerk, by finite differences at 1 kHz).

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "chunks/chunk_run.hpp"
#include "results_writer.hpp"

namespace comply::experiments {

struct ChunkOptions {
  std::filesystem::path out_dir = "out/chunks";
  chunks::RunSettings settings;
  std::vector<std::string> conditions{"stepped_15hz", "chunks_10hz", "chunks_15hz", "chunks_30hz"};
  bool pictures = true;
  std::ostream* progress = nullptr;
};

struct ChunkRow {
  chunks::Condition condition;
  chunks::RunResult result;
};

/// "stepped_<N>hz" or "chunks_<N>hz" as a condition; throws std::invalid_argument otherwise.
chunks::Condition chunkConditionOf(const std::string& name);

/// Runs every condition; writes <out>/<condition>.csv (every cycle), <out>/results.json,
/// <out>/table.md and, with pictures, <out>/chunks.png.
std::vector<ChunkRow> runChunks(const ChunkOptions& options);

ResultsTable chunkTable(const std::vector<ChunkRow>& rows);

/// The command line: returns 0 (the metrics are results, not checks).
int chunksCommand(const ChunkOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::experiments
