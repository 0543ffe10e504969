#include "csv_table.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace dtlab::experiments {
namespace {

// Splits one record; `in` may hold quoted fields with commas, quotes ("") and newlines.
bool read_record(std::istream& in, std::vector<std::string>& fields, bool& complete) {
  fields.clear();
  complete = true;
  std::string field;
  bool quoted = false;
  bool any = false;
  char c = 0;
  while (in.get(c)) {
    any = true;
    if (quoted) {
      if (c == '"') {
        if (in.peek() == '"') {
          in.get(c);
          field += '"';
        } else {
          quoted = false;
        }
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      fields.push_back(std::move(field));
      return true;
    } else {
      field += c;
    }
  }
  if (!any) return false;
  fields.push_back(std::move(field));
  complete = false;  // no final newline: the line was cut
  return true;
}

}  // namespace

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  throw std::out_of_range("no column " + name + " in the study's CSV");
}

double CsvTable::number(const std::vector<std::string>& row, const std::string& name) const {
  const std::string& cell = get(row, name);
  if (cell.empty()) return std::nan("");
  if (cell == "true") return 1.0;
  if (cell == "false") return 0.0;
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  return end != nullptr && *end == '\0' ? v : std::nan("");
}

CsvTable read_csv(const std::string& path, std::size_t* dropped) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  CsvTable table;
  std::vector<std::string> fields;
  bool complete = true;
  if (!read_record(in, table.header, complete)) return table;
  std::size_t bad = 0;
  while (read_record(in, fields, complete)) {
    if (complete && fields.size() == table.header.size()) {
      table.rows.push_back(fields);
    } else {
      ++bad;
    }
  }
  if (dropped != nullptr) *dropped = bad;
  return table;
}

namespace {

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    const std::string& f = fields[i];
    if (f.find_first_of(",\"\n\r") == std::string::npos) {
      line += f;
    } else {
      line += '"';
      for (const char c : f) {
        if (c == '"') line += '"';
        line += c;
      }
      line += '"';
    }
  }
  line += '\n';
  return line;
}

}  // namespace

CsvAppender::CsvAppender(const std::string& path, const std::vector<std::string>& header,
                         const std::vector<std::vector<std::string>>& keep) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << csv_line(header);
    for (const auto& row : keep) out << csv_line(row);
    out.flush();
    if (!out) throw std::runtime_error(temporary + ": cannot write");
  }
  std::filesystem::rename(temporary, path);
  out_.open(path, std::ios::app);
  if (!out_) throw std::runtime_error(path + ": cannot open for appending");
}

void CsvAppender::append(const std::vector<std::string>& row) {
  out_ << csv_line(row);
  out_.flush();
}

}  // namespace dtlab::experiments
