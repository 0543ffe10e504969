#pragma once
// Whether a thread reads only tetrahedra no other thread writes (the partitioned method's policy,
// methods/partition_sync.hpp). Such a policy has
//   confined()         whether other threads write the mesh in this pass at all
//   may_cross(tet, f)  whether the tetrahedron across face f of `tet` is one no other thread
//                      writes, so that a walk may step into it
//   acquire_across(t, record, f)  acquire(t) for t (whose record the caller has read) entered
//                      across its face f from a tetrahedron the thread holds (so only t's
//                      vertex opposite f is left to ask about)
// and then the walk stops at a face it may not cross (location/point_location.hpp), the cavity
// search asks it only for the cavity's own tetrahedra (insertion/cavity_search.hpp), and its thread
// needs no epochs for its slots (methods/parallel_run.hpp): nobody else reaches them.
#include <concepts>
#include <type_traits>

#include "mesh/tet_store.hpp"

namespace dtlab::engine {

template <class Policy>
inline constexpr bool kConfinedReads = requires(const Policy& policy, const Tet& tet) {
  { policy.may_cross(tet, 0) } -> std::same_as<bool>;
  { policy.confined() } -> std::same_as<bool>;
  { policy.acquire_across(TetId{}, tet, 0) } -> std::same_as<bool>;
};

// Every other thread's reads: the walk goes anywhere.
struct Unconfined {};

// What the walk of a thread with lock policy Sync asks: Sync itself where it confines the reads,
// else Unconfined (one walk for all the others).
template <class Sync>
using ReadConfinement = std::conditional_t<kConfinedReads<Sync>, Sync, Unconfined>;

}  // namespace dtlab::engine
