#pragma once
// The study's CSV: one header line, then one line per finished run (RFC 4180 quoting). Rows are
// appended and flushed as runs finish, so an interrupted study keeps them.
#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

namespace dtlab::experiments {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  // The column's index; throws std::out_of_range for a column the table does not have.
  [[nodiscard]] std::size_t column(const std::string& name) const;
  [[nodiscard]] const std::string& get(const std::vector<std::string>& row,
                                       const std::string& name) const {
    return row[column(name)];
  }
  // The cell as a number; NaN when it is empty or not a number.
  [[nodiscard]] double number(const std::vector<std::string>& row, const std::string& name) const;
};

// Reads a CSV written by CsvAppender. Lines whose field count differs from the header's (a line cut
// by an interrupt) are dropped and counted in `dropped`.
CsvTable read_csv(const std::string& path, std::size_t* dropped = nullptr);

class CsvAppender {
 public:
  // Writes `header` and the rows of `keep` (resume) to a temporary file that then replaces `path`
  // (an interrupt meanwhile leaves the old file whole), and opens it for appending.
  CsvAppender(const std::string& path, const std::vector<std::string>& header,
              const std::vector<std::vector<std::string>>& keep);
  // Appends and flushes one row.
  void append(const std::vector<std::string>& row);

 private:
  std::ofstream out_;
};

}  // namespace dtlab::experiments
