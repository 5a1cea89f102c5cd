#include "results_writer.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "comply/host/plot_script.hpp"

namespace comply::experiments {
namespace {

bool hasValue(const Value& value) {
  if (std::holds_alternative<std::monostate>(value)) {
    return false;
  }
  const double* number = std::get_if<double>(&value);
  return number == nullptr || std::isfinite(*number);
}

std::string cellText(const Value& value, const Column& column) {
  if (!hasValue(value)) {
    return column.missing;
  }
  if (const bool* flag = std::get_if<bool>(&value)) {
    return *flag ? "yes" : "no";
  }
  if (const std::int64_t* integer = std::get_if<std::int64_t>(&value)) {
    return std::to_string(*integer);
  }
  if (const double* number = std::get_if<double>(&value)) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(column.precision) << *number;
    return text.str();
  }
  return std::get<std::string>(value);
}

nlohmann::json jsonOf(const Value& value) {
  if (!hasValue(value)) {
    return nullptr;
  }
  return std::visit(
      [](const auto& held) -> nlohmann::json {
        if constexpr (std::is_same_v<std::decay_t<decltype(held)>, std::monostate>) {
          return nullptr;
        } else {
          return held;
        }
      },
      value);
}

std::string header(const Column& column) {
  return column.unit.empty() ? column.title : column.title + " [" + column.unit + "]";
}

void writeLine(const std::vector<std::string>& cells, std::ostream& out) {
  out << '|';
  for (const std::string& cell : cells) {
    out << ' ' << cell << " |";
  }
  out << '\n';
}

void writeRule(std::size_t columns, std::ostream& out) {
  out << '|';
  for (std::size_t i = 0; i < columns; ++i) {
    out << "---|";
  }
  out << '\n';
}

void writeRowPerResult(const ResultsTable& table, std::ostream& out) {
  std::vector<std::string> cells;
  for (const Column& column : table.columns) {
    if (column.in_table) {
      cells.push_back(header(column));
    }
  }
  writeLine(cells, out);
  writeRule(cells.size(), out);
  for (const std::vector<Value>& row : table.rows) {
    cells.clear();
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      if (table.columns[i].in_table) {
        cells.push_back(cellText(row.at(i), table.columns[i]));
      }
    }
    writeLine(cells, out);
  }
}

std::size_t columnIndex(const ResultsTable& table, const std::string& key) {
  for (std::size_t i = 0; i < table.columns.size(); ++i) {
    if (table.columns[i].key == key) {
      return i;
    }
  }
  throw std::invalid_argument("results table: no column '" + key + "'");
}

void writeColumnPerResult(const ResultsTable& table, std::ostream& out) {
  const ResultsTable::Transposed& layout = *table.transposed;
  const std::size_t label = columnIndex(table, layout.label_key);
  std::vector<std::string> cells{layout.corner};
  cells.insert(cells.end(), layout.reference_titles.begin(), layout.reference_titles.end());
  for (const std::vector<Value>& row : table.rows) {
    cells.push_back(cellText(row.at(label), table.columns[label]));
  }
  writeLine(cells, out);
  writeRule(cells.size(), out);
  for (std::size_t i = 0; i < table.columns.size(); ++i) {
    const Column& column = table.columns[i];
    if (i == label || !column.in_table) {
      continue;
    }
    cells = {header(column)};
    for (std::size_t r = 0; r < layout.reference_titles.size(); ++r) {
      cells.push_back(r < column.reference.size() ? column.reference[r] : column.missing);
    }
    for (const std::vector<Value>& row : table.rows) {
      cells.push_back(cellText(row.at(i), column));
    }
    writeLine(cells, out);
  }
}

}  // namespace

Column::Column(std::string key_in, std::string title_in, std::string unit_in, int precision_in)
    : key(std::move(key_in)),
      title(std::move(title_in)),
      unit(std::move(unit_in)),
      precision(precision_in) {}

Column& Column::missingAs(std::string text) {
  missing = std::move(text);
  return *this;
}

Column& Column::jsonOnly() {
  in_table = false;
  return *this;
}

Column& Column::withReference(std::vector<std::string> values) {
  reference = std::move(values);
  return *this;
}

void writeMarkdownTable(const ResultsTable& table, std::ostream& out) {
  if (table.transposed) {
    writeColumnPerResult(table, out);
  } else {
    writeRowPerResult(table, out);
  }
}

nlohmann::json toJson(const ResultsTable& table) {
  nlohmann::json results = nlohmann::json::array();
  for (const std::vector<Value>& row : table.rows) {
    nlohmann::json object = nlohmann::json::object();
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      object[table.columns[i].key] = jsonOf(row.at(i));
    }
    results.push_back(std::move(object));
  }
  return results;
}

void writeResults(const ResultsTable& table, const std::filesystem::path& out_dir) {
  std::ofstream(out_dir / "results.json") << toJson(table).dump(2) << "\n";
  std::ofstream markdown(out_dir / "table.md");
  writeMarkdownTable(table, markdown);
}

void printResults(const ResultsTable& table, const std::filesystem::path& out_dir,
                  std::string_view files, std::ostream& out) {
  writeMarkdownTable(table, out);
  out << "results in " << std::filesystem::absolute(out_dir).string();
  if (!files.empty()) {
    out << " (" << files << ")";
  }
  out << "\n";
}

void writeResultsAndPlots(const ResultsTable& table, const std::filesystem::path& out_dir,
                          const char* plot_script, bool pictures, std::ostream* progress) {
  writeResults(table, out_dir);
  if (pictures) {
    host::runPlotScript(plot_script, {out_dir.string()},
                        progress != nullptr ? *progress : std::cerr);
  }
}

}  // namespace comply::experiments
