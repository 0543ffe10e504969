#pragma once
// Star splaying (Shewchuk, SoCG 2005): the local repair of a tetrahedralization into the unique
// (perturbed) Delaunay one. Active vertices keep their own stars (vertex_star.hpp), built from the
// mesh's neighbours; stars that disagree are reconciled by offering vertices to each other until
// every active star agrees with every other and, at inactive vertices, with the mesh. The mesh is
// only read through MeshStars; writing the result back is the caller's (splay_repair.cpp).
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "repair/vertex_star.hpp"

namespace dtlab::engine {

// What the mesh being repaired says around one vertex.
class MeshStars {
 public:
  MeshStars() = default;
  MeshStars(const MeshStars&) = delete;
  MeshStars& operator=(const MeshStars&) = delete;
  virtual ~MeshStars() = default;
  // The mesh's tetrahedra that contain x (the vertex at infinity included where the mesh has it).
  // Called by several threads at once (StarSplayer::activate_all).
  virtual void tetrahedra_of(VertexId x, std::vector<Quad>& out) const = 0;
};

struct SplayCounts {
  std::uint64_t stars = 0;    // vertices whose star was built (activated)
  std::uint64_t offers = 0;   // vertices offered to stars
  std::uint64_t changes = 0;  // offers that changed a star
};

class StarSplayer {
 public:
  // `canonical[x]`: the lowest index of the points equal to point x; only those become vertices
  // (a duplicate is mapped to it wherever it is met). `pool`: four affinely independent
  // vertices, offered to a star whose candidates from the mesh do not span 3D. `near`: vertices
  // near x, for a vertex the mesh does not use.
  StarSplayer(const std::vector<predicates::Point3>& points, const MeshStars& mesh,
              const std::vector<VertexId>& canonical, const std::array<VertexId, 4>& pool,
              std::function<void(VertexId, std::vector<VertexId>&)> near);

  // Builds x's star from the mesh's neighbours of x and queues it for the consistency check.
  void activate(VertexId x);
  // activate(x) for each x of `xs`, in order, the stars built on `threads` threads: a new star
  // reads only the mesh and the points, so the stars, slots, counts and queue are those of
  // activating one by one, whatever the thread count (`near`, when called, too).
  void activate_all(const std::vector<VertexId>& xs, int threads);
  // Consistency enforcement until the queue is empty: then every active star's tetrahedron is in
  // the star of each of its active vertices and in the mesh at each inactive one, and every
  // tetrahedron of the mesh at an active vertex with an inactive vertex is in the active star.
  void run();
  // Offers active x and y to each other's stars; run() then reconciles what that changed.
  void introduce(VertexId x, VertexId y) {
    offer(x, y);
    offer(y, x);
  }

  [[nodiscard]] bool active(VertexId x) const { return slot_[x] >= 0; }
  [[nodiscard]] const std::vector<VertexId>& active_vertices() const { return active_; }
  [[nodiscard]] const VertexStar& star(VertexId x) const {
    return stars_[static_cast<std::size_t>(slot_[x])];
  }
  [[nodiscard]] const SplayCounts& counts() const { return counts_; }

 private:
  // What building one star needs for itself (one per thread in activate_all).
  struct BuildScratch {
    std::vector<Quad> around;
    std::vector<VertexId> candidates;
    std::vector<Quad> removed;
    StarScratch star;
    SplayCounts counts;
  };
  // Gives x a slot for its star (stars_ and active_ grow together), unless x is active or a
  // duplicate: then false.
  bool claim_slot(VertexId x);
  // x's star from the mesh's neighbours of x, into `star` (a fresh one).
  void build_star(VertexId x, VertexStar& star, BuildScratch& scratch) const;

  VertexStar& star_of(VertexId x) { return stars_[static_cast<std::size_t>(slot_[x])]; }
  void offer(VertexId to, VertexId w);
  void enqueue(VertexId x);
  void check(VertexId v);

  const std::vector<predicates::Point3>& points_;
  const MeshStars& mesh_;
  const std::vector<VertexId>& canonical_;
  std::array<VertexId, 4> pool_;
  std::function<void(VertexId, std::vector<VertexId>&)> near_;
  std::vector<int> slot_;  // vertex -> index in stars_, -1 when inactive
  std::vector<VertexStar> stars_;
  std::vector<VertexId> active_;
  std::deque<VertexId> queue_;
  std::vector<char> queued_;
  SplayCounts counts_;
  // Scratch, kept so that no call allocates once they have grown: offer()'s, activate()'s and
  // check()'s (activate() runs inside check(), so each has its own).
  std::vector<Quad> removed_;
  BuildScratch build_;
  std::vector<Quad> check_quads_;
  std::vector<Quad> check_around_;
  std::vector<Quad> check_keys_;
  std::vector<VertexId> check_link_;
  StarScratch scratch_;
};

}  // namespace dtlab::engine
