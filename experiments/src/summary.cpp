#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dtlab::experiments {

Aggregate aggregate(const std::vector<double>& values) {
  std::vector<double> v;
  for (const double x : values) {
    if (!std::isnan(x)) v.push_back(x);
  }
  Aggregate a;
  a.count = v.size();
  if (v.empty()) {
    a.mean = a.median = a.min = a.max = std::nan("");
    return a;
  }
  std::sort(v.begin(), v.end());
  double sum = 0.0;
  for (const double x : v) sum += x;
  a.mean = sum / static_cast<double>(v.size());
  const std::size_t mid = v.size() / 2;
  a.median = v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
  a.min = v.front();
  a.max = v.back();
  return a;
}

Aggregate aggregate_of(const CsvTable& table, const std::vector<const Row*>& rows,
                       const std::string& column) {
  std::vector<double> values;
  values.reserve(rows.size());
  for (const Row* row : rows) values.push_back(table.number(*row, column));
  return aggregate(values);
}

std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string mean_median_max(const Aggregate& a) {
  if (a.count == 0) return "-";
  return fixed(a.mean, 1) + " / " + fixed(a.median, 1) + " / " + fixed(a.max, 0);
}

std::string thousands(double value) {
  if (std::isnan(value)) return "-";
  const std::string digits = std::to_string(std::llround(value));
  std::string out;
  const std::size_t start = digits[0] == '-' ? 1 : 0;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > start && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string threads_cell(const CsvTable& table, const Row& row) {
  std::string cell = table.get(row, "threads");
  if (table.get(row, "oversubscribed") == "true") cell += " (oversubscribed)";
  return cell;
}

bool is_ok(const CsvTable& table, const Row& row) {
  return table.get(row, "status") == "ok";
}

std::string MarkdownTable::str() const {
  std::string out = "|";
  for (const std::string& h : header_) out += " " + h + " |";
  out += "\n|";
  for (std::size_t i = 0; i < header_.size(); ++i) out += i == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& row : rows_) {
    out += "|";
    for (const std::string& cell : row) out += " " + cell + " |";
    out += "\n";
  }
  return out;
}

std::string failed_runs(const CsvTable& table) {
  std::string out;
  for (const Row& row : table.rows) {
    const std::string& status = table.get(row, "status");
    if (status == "ok") continue;
    out +=
        "- `" + table.get(row, "run_key") + "`: " + status + ": " + table.get(row, "error") + "\n";
  }
  return out.empty() ? out : "\nRuns that ended without a result:\n\n" + out;
}

}  // namespace dtlab::experiments
