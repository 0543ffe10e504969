#pragma once
// A small hash map from integer keys to values, emptied in O(1) by an epoch: the scratch space
// of one insertion (the cavity's marks, the cavity's boundary edges), reused for the next without
// clearing. Open addressing with linear probing, grown at half load; no erase.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dtlab::engine {

template <class Key, class Value>
class EpochTable {
 public:
  // Empties the table.
  void clear() {
    if (entries_.empty()) entries_.resize(kInitialSize);
    if (++epoch_ == 0) {  // wrapped: entries of an old epoch could look current
      for (Entry& e : entries_) e.epoch = 0;
      epoch_ = 1;
    }
    count_ = 0;
  }
  // The value stored for key, or nullptr.
  Value* find(Key key) {
    for (std::size_t i = slot_of(key);; i = (i + 1) & (entries_.size() - 1)) {
      Entry& e = entries_[i];
      if (e.epoch != epoch_) return nullptr;
      if (e.key == key) return &e.value;
    }
  }
  // key must not be in the table.
  void insert(Key key, Value value) {
    if (2 * (count_ + 1) > entries_.size()) grow();
    place(key, value);
    ++count_;
  }
  [[nodiscard]] std::size_t size() const { return count_; }

 private:
  static constexpr std::size_t kInitialSize = 256;
  struct Entry {
    Key key{};
    std::uint32_t epoch = 0;
    Value value{};
  };
  // Fibonacci hashing (Knuth, TAOCP 6.4): the top bits of key times 2^64 / golden ratio.
  [[nodiscard]] std::size_t slot_of(Key key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ULL) >>
                                    shift_);
  }
  void place(Key key, Value value) {
    std::size_t i = slot_of(key);
    while (entries_[i].epoch == epoch_) i = (i + 1) & (entries_.size() - 1);
    entries_[i] = {key, epoch_, value};
  }
  void grow() {
    std::vector<Entry> old;
    old.swap(entries_);
    entries_.assign(2 * old.size(), Entry{});
    --shift_;
    for (const Entry& e : old) {
      if (e.epoch == epoch_) place(e.key, e.value);
    }
  }

  std::vector<Entry> entries_;
  std::uint32_t epoch_ = 0;
  std::size_t count_ = 0;
  int shift_ = 64 - 8;  // log2(kInitialSize) top bits
};

}  // namespace dtlab::engine
