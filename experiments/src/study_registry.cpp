#include <cmath>

#include "studies/studies.hpp"
#include "summary.hpp"

namespace dtlab::experiments {

const std::vector<Study>& all_studies() {
  static const std::vector<Study> studies = {
      burglary_errors_study(), predicate_errors_study(), speedup_study(),   breakdown_study(),
      flips_study(),           deadlocks_study(),        hull_loss_study(), compare_study()};
  return studies;
}

RunSpec dtlab_run(const std::string& input, const std::string& source, std::int64_t size,
                  std::uint64_t seed) {
  RunSpec spec;
  spec.input = input;
  spec.source = source;
  spec.size = size;
  spec.options.seed = seed;
  return spec;
}

std::string thousands(double value) {
  if (std::isnan(value)) return "-";
  std::string digits = std::to_string(static_cast<long long>(std::llround(value)));
  std::string out;
  const std::size_t start = digits[0] == '-' ? 1 : 0;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > start && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string threads_cell(const CsvTable& table, const std::vector<const Row*>& rows) {
  const Row& row = *rows.front();
  std::string cell = table.get(row, "threads");
  if (table.get(row, "oversubscribed") == "true") cell += " (oversubscribed)";
  return cell;
}

bool is_ok(const CsvTable& table, const Row& row) {
  return table.get(row, "status") == "ok";
}

}  // namespace dtlab::experiments
