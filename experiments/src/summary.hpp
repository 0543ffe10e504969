#pragma once
// Helpers the studies' summaries share: rows grouped by key columns, aggregates over a group,
// number formatting and Markdown tables.
#include <cstddef>
#include <string>
#include <vector>

#include "csv_table.hpp"

namespace dtlab::experiments {

using Row = std::vector<std::string>;

struct RowGroup {
  std::vector<std::string> key;  // the values of the key columns
  std::vector<const Row*> rows;
};

// Groups the rows for which `keep` is true by the values of `keys`, in first-seen order.
template <class Keep>
std::vector<RowGroup> group_rows(const CsvTable& table, const std::vector<std::string>& keys,
                                 Keep keep) {
  std::vector<RowGroup> groups;
  for (const Row& row : table.rows) {
    if (!keep(row)) continue;
    std::vector<std::string> key;
    for (const std::string& k : keys) key.push_back(table.get(row, k));
    RowGroup* found = nullptr;
    for (RowGroup& g : groups) {
      if (g.key == key) found = &g;
    }
    if (found == nullptr) {
      groups.push_back({key, {}});
      found = &groups.back();
    }
    found->rows.push_back(&row);
  }
  return groups;
}

struct Aggregate {
  std::size_t count = 0;  // numbers among the values (empty cells are left out)
  double mean = 0.0;
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
};

Aggregate aggregate(const std::vector<double>& values);
Aggregate aggregate_of(const CsvTable& table, const std::vector<const Row*>& rows,
                       const std::string& column);

// Fixed decimals; "-" for NaN.
std::string fixed(double value, int decimals);
// "mean / median / max" of a count.
std::string mean_median_max(const Aggregate& a);
// A whole number with thousands separators: 12,345; "-" for NaN.
std::string thousands(double value);
// The row's thread count, with "(oversubscribed)" when it exceeds the hardware threads.
std::string threads_cell(const CsvTable& table, const Row& row);
// The run finished with a result (status ok).
bool is_ok(const CsvTable& table, const Row& row);

class MarkdownTable {
 public:
  explicit MarkdownTable(std::vector<std::string> header) : header_(std::move(header)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  [[nodiscard]] std::string str() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

// Rows whose run ended without a result ("error", "crashed"), as a Markdown list; empty if none.
std::string failed_runs(const CsvTable& table);

}  // namespace dtlab::experiments
