#pragma once
// What every experiment leaves in its output folder besides its runs: table.md (the table the
// README quotes), results.json (one object per result row, for scripts) and plots drawn by the
// Python scripts under scripts/. An experiment describes its columns once and computes its rows;
// both files come from that description, so they cannot disagree.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace comply::experiments {

/// One cell. std::monostate and non-finite numbers are "no value": null in results.json, the
/// column's `missing` text in the table.
using Value = std::variant<std::monostate, bool, std::int64_t, double, std::string>;

struct Column {
  /// A column in both files; numbers with `precision` decimals in the table.
  Column(std::string key, std::string title, std::string unit = {}, int precision = 3);

  Column& missingAs(std::string text);  ///< table text for no value (default "-")
  Column& jsonOnly();                   ///< left out of the table
  Column& withReference(std::vector<std::string> values);

  std::string key;    ///< name in results.json
  std::string title;  ///< table header, followed by " [unit]" when there is a unit
  std::string unit;
  int precision = 3;
  std::string missing = "-";
  bool in_table = true;
  /// Transposed tables: values from elsewhere (e.g. a paper) printed before the results, one per
  /// ResultsTable::Transposed::reference_titles.
  std::vector<std::string> reference;
};

struct ResultsTable {
  /// One table row per column and one table column per result row, headed by `label_key`'s
  /// value: for a few conditions compared on many metrics, next to reference values.
  struct Transposed {
    std::string corner;     ///< header of the metric names' column
    std::string label_key;  ///< the column whose values head the result columns
    std::vector<std::string> reference_titles;
  };

  std::vector<Column> columns;
  std::vector<std::vector<Value>> rows;  ///< one value per column
  std::optional<Transposed> transposed;
};

/// The table in markdown, as table.md holds it.
void writeMarkdownTable(const ResultsTable& table, std::ostream& out);

/// An array with one object per row, keyed by the columns' keys.
nlohmann::json toJson(const ResultsTable& table);

/// Writes <out_dir>/results.json and <out_dir>/table.md.
void writeResults(const ResultsTable& table, const std::filesystem::path& out_dir);

/// What an experiment's command prints on `out`: the table, then the folder of the results and
/// what it holds (`files`: empty to name none).
void printResults(const ResultsTable& table, const std::filesystem::path& out_dir,
                  std::string_view files, std::ostream& out);

/// The options of a run whose progress goes to `err`.
template <typename Options>
Options withProgress(const Options& options, std::ostream& err) {
  Options run = options;
  run.progress = &err;
  return run;
}

/// writeResults(), then, with `pictures`, the plots scripts/<plot_script> draws from the folder;
/// the script's messages go to `progress` (std::cerr when null).
void writeResultsAndPlots(const ResultsTable& table, const std::filesystem::path& out_dir,
                          const char* plot_script, bool pictures, std::ostream* progress);

}  // namespace comply::experiments
