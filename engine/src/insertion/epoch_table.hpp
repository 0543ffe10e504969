#pragma once
// A small hash map from integer keys to values, emptied in O(1) by an epoch: the scratch space
// of one insertion (the cavity search's marks), reused for the next without clearing. Open
// addressing with linear probing, grown at half load; no erase. Each clear() goes back to the
// smallest table within the memory kept: one huge cavity (cospherical input) must not leave
// every later, small one probing a table spread over megabytes.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace dtlab::engine {

template <class Key, class Value>
class EpochTable {
 public:
  // Empties the table.
  void clear() {
    if (entries_.empty()) entries_.resize(kInitialSize);
    set_used(kInitialSize);
    next_epoch();
    count_ = 0;
  }
  // The value stored for key, or nullptr.
  Value* find(Key key) {
    for (std::size_t i = slot_of(key);; i = (i + 1) & (used_ - 1)) {
      Entry& e = entries_[i];
      if (e.epoch != epoch_) return nullptr;
      if (e.key == key) return &e.value;
    }
  }
  // The value stored for key, and false; or, when key is absent, a new entry for it with `fresh`
  // as its value, and true: one probe sequence where find() then insert() take two.
  std::pair<Value*, bool> find_or_insert(Key key, Value fresh) {
    if (2 * (count_ + 1) > used_) grow();
    std::size_t i = slot_of(key);
    for (; entries_[i].epoch == epoch_; i = (i + 1) & (used_ - 1)) {
      if (entries_[i].key == key) return {&entries_[i].value, false};
    }
    entries_[i] = {key, epoch_, fresh};
    ++count_;
    return {&entries_[i].value, true};
  }
  // key must not be in the table. Out of line: a search's first entry, once per search.
  [[gnu::noinline]] void insert(Key key, Value value) {
    if (2 * (count_ + 1) > used_) grow();
    place(key, value);
    ++count_;
  }
  [[nodiscard]] std::size_t size() const { return count_; }
  // Entries in use now, and kept allocated (for tests).
  [[nodiscard]] std::size_t used_capacity() const { return used_; }
  [[nodiscard]] std::size_t allocated_capacity() const { return entries_.size(); }

 private:
  static constexpr std::size_t kInitialSize = 256;
  struct Entry {
    Key key{};
    std::uint32_t epoch = 0;
    Value value{};
  };
  void set_used(std::size_t used) {
    used_ = used;
    shift_ = 64 - __builtin_ctzll(used);
  }
  void next_epoch() {
    if (++epoch_ == 0) {  // wrapped: entries of an old epoch could look current
      for (Entry& e : entries_) e.epoch = 0;
      epoch_ = 1;
    }
  }
  // Fibonacci hashing (Knuth, TAOCP 6.4): the top bits of key times 2^64 / golden ratio.
  [[nodiscard]] std::size_t slot_of(Key key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ULL) >>
                                    shift_);
  }
  void place(Key key, Value value) {
    std::size_t i = slot_of(key);
    while (entries_[i].epoch == epoch_) i = (i + 1) & (used_ - 1);
    entries_[i] = {key, epoch_, value};
  }
  // Twice the entries in use: the current ones move out, a new epoch empties the table, and
  // they go back in at their new places. Out of line: rare, and inlined into the cavity search
  // (GCC's choice in some translation units) it crowded the hot loop's registers.
  [[gnu::noinline]] void grow() {
    moving_.clear();
    for (std::size_t i = 0; i < used_; ++i) {
      if (entries_[i].epoch == epoch_) moving_.push_back(entries_[i]);
    }
    set_used(2 * used_);
    if (entries_.size() < used_) entries_.resize(used_);
    next_epoch();
    for (const Entry& e : moving_) place(e.key, e.value);
  }

  std::vector<Entry> entries_;  // the first used_ are the table
  std::vector<Entry> moving_;   // grow()'s scratch
  std::size_t used_ = kInitialSize;
  std::uint32_t epoch_ = 0;
  std::size_t count_ = 0;
  int shift_ = 64 - 8;  // log2(used_) top bits
};

}  // namespace dtlab::engine
