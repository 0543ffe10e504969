#pragma once
// What every writer of the mesh by replacements needs, one per thread: the mesh, the run's
// options and stats, the lock method's policy (sync.hpp), the geometry (the predicates with the
// vertex at infinity), the slots and the replacement. The flips (flips.hpp), the inserter
// (inserter.hpp) and the Lawson pass (lawson_pass.hpp) build on it, as base classes, so that
// their hot loops read these members from one object.
#include <memory>
#include <type_traits>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "insertion/sync.hpp"
#include "insertion/tet_replacement.hpp"
#include "location/location_policy.hpp"
#include "mesh/mesh_geometry.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/slot_allocator.hpp"
#include "mesh/slot_reclaimer.hpp"
#include "support/phase_clock.hpp"

namespace dtlab::engine {

template <class K, class Sync = NoSync>
class MeshEditor {
  // Declared first, so initialized before mesh_ and sync_ refer to them: the sequential engine's
  // own mesh and policy.
  std::unique_ptr<SharedMesh> owned_;
  NoSync own_sync_;

 public:
  // The sequential engine: owns its mesh, reusing dead slots where the location mode does.
  MeshEditor(const std::vector<Point3>& points, const TriangulateOptions& options,
             TriangulationStats& stats)
      : MeshEditor(std::make_unique<SharedMesh>(points), nullptr, options, stats, nullptr,
                   nullptr) {
    if (options.max_tetrahedra > 0) mesh_.tets.set_capacity(options.max_tetrahedra);
    mesh_.tets.keep_children(location_.history);
    mesh_.tets.keep_lock_words(Sync::kLocks);
  }
  // One thread of a parallel method, or a pass after the run, on a shared mesh. With a reclaimer
  // the thread reuses dead slots where the location mode does (slot_reclaimer.hpp), as does a
  // thread whose policy confines its reads (sync.hpp: nobody else can reach its dead slots);
  // otherwise (the post-check's flips) it keeps every slot and writes the DAG children where the
  // store keeps them.
  MeshEditor(SharedMesh& mesh, const TriangulateOptions& options, TriangulationStats& stats,
             Sync& sync, SlotReclaimer* reclaimer = nullptr)
      : MeshEditor(nullptr, &mesh, options, stats, &sync, reclaimer) {}

  MeshEditor(const MeshEditor&) = delete;
  MeshEditor& operator=(const MeshEditor&) = delete;

  SharedMesh& mesh() { return mesh_; }
  [[nodiscard]] bool owns_mesh() const { return owned_ != nullptr; }
  [[nodiscard]] std::uint64_t predicate_calls() const { return geometry_.predicate_calls(); }
  // Slots in use: the DAG's nodes, or (reusing) the live tetrahedra and the free slots.
  [[nodiscard]] std::uint64_t store_slots() const { return mesh_.tets.size(); }

 protected:
  using Replaced = typename TetReplacement<Sync>::Replaced;

  SharedMesh& mesh_;
  const TriangulateOptions& options_;
  TriangulationStats& stats_;
  Sync* sync_;
  LocationPolicy location_;
  bool recycle_;  // dead slots are reused (the location mode's slot_reuse, where it can be)
  MeshGeometry<K> geometry_;
  SlotAllocator slots_;
  TetReplacement<Sync> replacement_;

 private:
  MeshEditor(std::unique_ptr<SharedMesh> owned, SharedMesh* shared,
             const TriangulateOptions& options, TriangulationStats& stats, Sync* sync,
             SlotReclaimer* reclaimer)
      : owned_(std::move(owned)),
        mesh_(owned_ ? *owned_ : *shared),
        options_(options),
        stats_(stats),
        sync_(policy(sync)),
        location_(resolve_location(options.location)),
        recycle_(location_.slot_reuse &&
                 (owned_ != nullptr || reclaimer != nullptr || kConfinedReads<Sync>)),
        geometry_(mesh_),
        slots_(mesh_.tets, recycle_, reclaimer, /*track_attempts=*/Sync::kLocks),
        replacement_(mesh_, *sync_, slots_, !recycle_) {
    PhaseClock::calibrate();  // here, not inside the first insertion's phases
  }
  // The given policy, or the sequential engine's own (NoSync only: it owns its mesh).
  Sync* policy(Sync* given) {
    if constexpr (std::is_same_v<Sync, NoSync>) {
      return given != nullptr ? given : &own_sync_;
    } else {
      return given;
    }
  }
};

}  // namespace dtlab::engine
