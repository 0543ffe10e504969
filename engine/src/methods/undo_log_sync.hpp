#pragma once
// What optimistic-detect and optimistic-prevent share (paper Fig. 6): a thread that must not wait
// gives its insertion up and restores the mesh exactly from an undo log. Every tetrahedron is
// saved once, before its first write (its lock word then carries LockTable::kLogged, so the owner
// asks its own word, already in cache, instead of a set); new tetrahedra are never logged but
// retired on rollback. The two methods differ only in acquire(), in their own files.
#include <array>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <vector>

#include "insertion/sync.hpp"
#include "methods/lock_words.hpp"

namespace dtlab::engine {

class UndoLogSync : public LockWords {
 public:
  using LockWords::LockWords;

  void before_write(TetId t) {
    // Logged once; created tetrahedra carry kLogged from birth (retired whole on rollback). Only
    // this thread writes the word while it holds t. release: a find_cycle that reads this value
    // still synchronizes with everything before the compare-and-swap that took t.
    std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
    const std::uint32_t held = word.load(std::memory_order_relaxed);
    if ((held & LockTable::kLogged) != 0) return;
    word.store(held | LockTable::kLogged, std::memory_order_release);
    const Tet& tet = mesh_.tets[t];
    // Only live tetrahedra are written: each is the located leaf (checked after locking), an old
    // one of the replacement, or a neighbour of a locked live one (whoever kills it rewrites that
    // reference, under the lock). So rollback makes every logged one alive again without
    // having recorded its aliveness.
    assert(mesh_.tets.is_alive(t, std::memory_order_relaxed));
    // Filled in place: an entry built on the stack from overlapping stores and copied by wider
    // loads stalled on store forwarding.
    Saved& s = log_.emplace_back();
    s.tet = t;
    s.neighbor = tet.neighbor;
    if (mesh_.tets.has_children()) {
      const auto& children = mesh_.tets.children(t);
      for (std::size_t i = 0; i < 4; ++i) s.child[i] = children[i].load(std::memory_order_relaxed);
    }
  }

  // last_write: this replacement ends the insertion (a cavity's), so rollback() cannot follow it
  // and the list it reads need not hold t.
  void created(TetId t, bool last_write = false) {
    // Owned before it is published: nobody can lock it before this thread lets go. Never logged.
    // Not alive yet (the replacement sets it alive once linked).
    mesh_.tets.lock_word(t).store(self_ | LockTable::kLogged, std::memory_order_relaxed);
    held_.push_back(t);
    if (last_write) {
      ended_ = true;
    } else {
      created_.push_back(t);
    }
  }
  void killed(TetId /*t*/, bool /*last_write*/ = false) {}

  void commit() {
    log_.clear();
    created_.clear();
    release_held();
    ended_ = false;
  }

  // Restores every logged tetrahedron, then retires the new ones (dead, no children: a reader
  // that reaches one restarts its descent), then unlocks.
  void rollback() {
    assert(!ended_);  // nothing after a last write can be refused
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      Tet& tet = mesh_.tets[it->tet];
      for (int f = 0; f < 4; ++f) {  // walking threads read these without a lock
        store_neighbor(tet, f, it->neighbor[static_cast<std::size_t>(f)]);
      }
      for (std::size_t i = 0; i < 4; ++i)
        if (mesh_.tets.has_children()) {
          mesh_.tets.children(it->tet)[i].store(it->child[i], std::memory_order_relaxed);
        }
      mesh_.tets.set_alive(it->tet, true);
    }
    for (const TetId t : created_) {
      if (mesh_.tets.has_children()) {
        for (auto& c : mesh_.tets.children(t)) c.store(kNoTet, std::memory_order_relaxed);
      }
      mesh_.tets.set_alive(t, false);
    }
    log_.clear();
    created_.clear();
    release_held();
  }

  // A lock refused in the middle of legalization: the insertion is given up.
  Resume resume() {
    assert(!ended_);
    return Resume::GiveUp;
  }
  // Never called: resume() never says Stop.
  void mark_suspicious(TetId /*t*/) {}

 private:
  struct Saved {
    TetId tet;
    std::array<FaceRef, 4> neighbor;
    std::array<TetId, 4> child;
  };

  TetIdList created_;
  bool ended_ = false;  // a last write happened in this insertion (checked in debug builds)
  std::vector<Saved> log_;
};

}  // namespace dtlab::engine
