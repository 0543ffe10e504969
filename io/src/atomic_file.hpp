#pragma once
// Writes to PATH.tmp-PID and renames it to PATH on commit(); removes the temporary otherwise.
#include <unistd.h>
#include <cstdio>
#include <fstream>
#include <string>

#include "dtlab/io/input_error.hpp"

namespace dtlab::io::detail {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path)
      : path_(std::move(path)), temp_(path_ + ".tmp-" + std::to_string(::getpid())) {
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error(path_ + ": cannot open for writing");
    out_.exceptions(std::ios::badbit | std::ios::failbit);
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (!committed_) {
      // No exception from here: a commit whose rename failed has closed the stream already, and
      // closing it again set failbit, which the stream threw from this destructor (a crash, found
      // by IoTest.FailedWriteLeavesNoFile).
      out_.exceptions(std::ios::goodbit);
      if (out_.is_open()) out_.close();
      std::remove(temp_.c_str());
    }
  }
  std::ofstream& stream() { return out_; }
  void commit() {
    out_.close();
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
      std::remove(temp_.c_str());
      throw std::runtime_error(path_ + ": cannot rename the finished output into place");
    }
    committed_ = true;
  }

 private:
  std::string path_;
  std::string temp_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace dtlab::io::detail
