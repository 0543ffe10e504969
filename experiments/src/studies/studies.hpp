#pragma once
// The studies of `dtlab experiment`, one file each.
#include "../study.hpp"
#include "../summary.hpp"

namespace dtlab::experiments {

Study burglary_errors_study();
Study predicate_errors_study();
Study speedup_study();
Study breakdown_study();
Study flips_study();
Study deadlocks_study();
Study hull_loss_study();
Study compare_study();

// A run of the dtlab engine on `source` with the given seed; the rest default.
RunSpec dtlab_run(const std::string& input, const std::string& source, std::int64_t size,
                  std::uint64_t seed);
// "12,345" and "oversubscribed" marks: the shared cell formats.
std::string thousands(double value);
std::string threads_cell(const CsvTable& table, const std::vector<const Row*>& rows);
bool is_ok(const CsvTable& table, const Row& row);

}  // namespace dtlab::experiments
