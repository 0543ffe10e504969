#pragma once
// Line-oriented scanning of text formats, with the line number for error messages.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "dtlab/io/input_error.hpp"

namespace dtlab::io::detail {

class TextScanner {
 public:
  TextScanner(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

  // Where the next "\n" and the next "\r" lie, at or after the position last asked
  // (text.size() when none; npos before the first line), kept from line to line: each is then
  // searched for once over the text (by memchr), not once a line, and a file without one (no
  // "\r" in most files, no "\n" in old Mac files) is not searched to its end for every row.
  struct LineEnds {
    std::size_t newline = std::string_view::npos;
    std::size_t cr = std::string_view::npos;
  };
  // A line of `text` from `pos`: it ends at "\n", "\r\n" or a lone "\r" (old Mac files: read
  // as one line, their rows were lost as extra columns of the first) or at the text's end.
  // Returns the line's end; `next` is where the line after it starts.
  static std::size_t line_end(std::string_view text, std::size_t pos, std::size_t& next,
                              LineEnds& ends) {
    if (ends.newline == std::string_view::npos || ends.newline < pos) {
      ends.newline = std::min(text.find('\n', pos), text.size());
    }
    if (ends.cr == std::string_view::npos || ends.cr < pos) {
      ends.cr = std::min(text.find('\r', pos), text.size());
    }
    if (ends.cr >= ends.newline) {
      next = std::min(ends.newline + 1, text.size());
      return ends.newline;
    }
    // "\r\n" (or a "\r" ending the text), else a lone "\r".
    next = ends.cr + 1 == ends.newline ? std::min(ends.newline + 1, text.size()) : ends.cr + 1;
    return ends.cr;
  }

  // Next line that is neither blank nor a comment ('#' starts a comment); false at the end.
  bool next_content_line(std::string_view& line) {
    while (pos_ < text_.size()) {
      std::size_t next = 0;
      const std::size_t end = line_end(text_, pos_, next, ends_);
      std::string_view raw = text_.substr(pos_, end - pos_);
      pos_ = next;
      ++line_number_;
      if (const std::size_t hash = raw.find('#'); hash != std::string_view::npos) {
        raw = raw.substr(0, hash);
      }
      raw = trim(raw);
      if (!raw.empty()) {
        line = raw;
        return true;
      }
    }
    return false;
  }

  [[nodiscard]] std::size_t line_number() const { return line_number_; }
  [[nodiscard]] const std::string& name() const { return name_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name_ + ":" + std::to_string(line_number_) + ": " + what);
  }

  static std::string_view trim(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
  }
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  }

  // Splits off the next whitespace-separated token of `line`; false when none is left.
  static bool next_token(std::string_view& line, std::string_view& token) {
    while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
    if (line.empty()) return false;
    std::size_t n = 0;
    while (n < line.size() && !is_space(line[n])) ++n;
    token = line.substr(0, n);
    line.remove_prefix(n);
    return true;
  }

  // Parses a finite double token, or fails naming `what`.
  double parse_double(std::string_view token, const char* what) const {
    double v = 0.0;
    const char* first = token.data();
    if (!token.empty() && token.front() == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
      if (ec == std::errc::result_out_of_range) {
        fail(std::string(what) + " '" + std::string(token) + "' is out of the range of double");
      }
      fail(std::string("expected a number for ") + what + ", got '" + std::string(token) + "'");
    }
    if (!std::isfinite(v)) fail(std::string(what) + " is not finite (" + std::string(token) + ")");
    return v;
  }

  std::int64_t parse_integer(std::string_view token, const char* what) const {
    std::int64_t v = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
      fail(std::string("expected an integer for ") + what + ", got '" + std::string(token) + "'");
    }
    return v;
  }

 private:
  std::string_view text_;
  std::string name_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
  LineEnds ends_;
};

}  // namespace dtlab::io::detail
