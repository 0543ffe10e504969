#pragma once
// The Sync contract: how the inserter (inserter.hpp) asks a lock method for permission and tells
// it what it wrote, so that one insertion kernel serves every method. A method's policy is a class
// with these members (methods/ implements them; the sequential engine's is NoSync below):
//   kLocks             whether it locks at all (false compiles the lock calls away)
//   acquire(t)         lock t before reading it for change or writing it; false: give up
//   before_write(t)    t is about to be written for the first time in this insertion (undo log;
//                      a policy with kReglueOnUndo is told only of the tetrahedra that die:
//                      mesh/topology_commit.hpp)
//   created(t, last)   t is new, owned by this thread from birth; `last`: the insertion's last
//                      write (a cavity's), after which nothing can be refused
//   killed(t, last)    t died by this thread's write
//   commit()           the insertion is complete: unlock everything
//   rollback()         give the insertion up: restore what was written, unlock
//   resume()           a lock was refused during legalization: what now (Resume)
//   mark_suspicious(t) burglary: t's faces are for the post-check
// The inserter calls them in this order per insertion: acquire for the located tetrahedron, then
// acquire for every tetrahedron a replacement reads or writes, before_write for each before the
// first write, created and killed as the replacement commits, then commit or rollback.
// A policy may also confine its thread's reads (the partitioned method's):
// mesh/read_confinement.hpp.
#include "mesh/read_confinement.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

// What a lock refused during legalization leads to: GiveUp (undo the insertion: detect, prevent),
// Continue (a burglary victim whose part of the mesh is intact) or Stop (a burglary victim whose
// part was changed: the rest of its legalization is dropped and marked suspicious).
enum class Resume { GiveUp, Continue, Stop };

// The sequential engine's synchronization: none. Every hook is an empty inline function, so the
// sequential build pays nothing for the parallel methods' policy slots.
struct NoSync {
  static constexpr bool kLocks = false;
  bool acquire(TetId /*t*/) { return true; }
  void before_write(TetId /*t*/) {}
  void created(TetId /*t*/, bool /*last_write*/ = false) {}
  void commit() {}
  void rollback() {}
  void killed(TetId /*t*/, bool /*last_write*/ = false) {}
  Resume resume() { return Resume::GiveUp; }
  void mark_suspicious(TetId /*t*/) {}
};

}  // namespace dtlab::engine
