#pragma once
#include <stdexcept>
#include <string>

namespace dtlab::io {

// Bad input: the message names the file and, where known, the line or element.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dtlab::io
