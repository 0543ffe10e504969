// Star splaying's write-back (splay_write_back.hpp).
#include "repair/splay_write_back.hpp"

#include <algorithm>
#include <stdexcept>

#include "insertion/sync.hpp"
#include "mesh/face_key.hpp"
#include "mesh/topology_commit.hpp"

namespace dtlab::engine {

void write_back(SharedMesh& mesh, StarSplayer& splayer, const std::vector<VertexId>& canonical,
                const std::vector<TetId>& live, const WalkedMeshStars* walked, SplayStats& stats) {
  // Write back. New: every tetrahedron of an active star, once. Old: every live tetrahedron at an
  // active vertex, replaced. The enforcement made the two agree wherever an inactive vertex is
  // involved, so the new ones fit the kept ones face to face. A broken mesh can defeat that at an
  // inactive vertex (the fast kernel's mesh may hold a face in two pairs of tetrahedra, all locally
  // Delaunay): the vertices of every face that does not fit are splayed too, and the plan is made
  // again.
  std::vector<TetId> dying;
  std::vector<Quad> created;
  std::vector<FaceEntry> faces;
  for (;;) {
    std::vector<Quad> fresh;
    for (const VertexId v : splayer.active_vertices()) {
      for (const Quad& q : splayer.star(v).tetrahedra()) {
        VertexId owner = v;
        for (const VertexId y : q) {
          if (y != kInfiniteVertex && splayer.active(y)) owner = std::min(owner, y);
        }
        if (owner == v) fresh.push_back(q);
      }
    }
    dying.clear();
    if (walked != nullptr) {
      // The walks around the active vertices find the same tetrahedra as the pass below, without
      // reading the whole mesh (sorted here; the order does not change the result).
      std::vector<TetId> around_active;
      for (const VertexId v : splayer.active_vertices()) {
        walked->tetrahedron_ids_of(v, around_active);
        dying.insert(dying.end(), around_active.begin(), around_active.end());
      }
      std::sort(dying.begin(), dying.end());
      dying.erase(std::unique(dying.begin(), dying.end()), dying.end());
    } else {
      for (const TetId i : live) {
        bool touched = false;
        for (const VertexId v : mesh.tets[i].vertex) {
          touched |= v != kInfiniteVertex && splayer.active(v);
        }
        if (touched) dying.push_back(i);
      }
    }
    std::vector<char> is_dying(mesh.tets.size(), 0);  // the flips may have added slots
    for (const TetId t : dying) is_dying[t] = 1;
    faces.clear();
    for (const TetId t : dying) {
      const Tet& tet = mesh.tets[t];
      for (std::size_t f = 0; f < 4; ++f) {
        const FaceRef outside = tet.neighbor[f];
        if (is_dying[ref_tet(outside)] == 0) {
          faces.push_back({face_key(tet.vertex, static_cast<int>(f)), outside, false});
        }
      }
    }
    created = std::move(fresh);
    for (std::size_t j = 0; j < created.size(); ++j) {
      for (std::size_t f = 0; f < 4; ++f) {
        faces.push_back({face_key(created[j], static_cast<int>(f)),
                         face_ref(static_cast<TetId>(j), static_cast<int>(f)), true});
      }
    }
    std::sort(faces.begin(), faces.end(), by_face_key);
    // A face fits when exactly two entries have its key, at least one of them new.
    std::vector<VertexId> grow;
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i;
      bool any_new = false;
      while (j < faces.size() && faces[j].key == faces[i].key) any_new |= faces[j++].is_new;
      if (j - i != 2 || !any_new) {
        auto add = [&](VertexId v) {
          if (v != kInfiniteVertex && canonical[v] == v && !splayer.active(v)) grow.push_back(v);
        };
        for (const VertexId v : faces[i].key.vertices()) add(v);
        // The tetrahedra on the kept side: their other vertices too.
        for (std::size_t k = i; k < j; ++k) {
          if (faces[k].is_new) continue;
          for (const VertexId v : mesh.tets[ref_tet(faces[k].ref)].vertex) add(v);
        }
        if (grow.empty()) {
          throw std::logic_error(
              "star splaying: the repaired region does not fit the mesh around it");
        }
      }
      i = j;
    }
    if (grow.empty()) break;
    ++stats.regrown;
    for (const VertexId v : grow) splayer.activate(v);
    splayer.run();
  }
  stats.stars = splayer.counts().stars;
  stats.offers = splayer.counts().offers;
  stats.changes = splayer.counts().changes;
  // Through the store's one write path, on this thread alone (no locks) and in fresh slots.
  NoSync no_sync;
  StoreSlots fresh_slots(mesh.tets);
  TopologyCommit<NoSync, StoreSlots> commit(mesh, no_sync, fresh_slots, /*recycle=*/false);
  std::vector<TetId> ids(created.size());
  for (std::size_t j = 0; j < created.size(); ++j) {
    ids[j] = commit.allocate();
    commit.record(ids[j]).vertex = created[j];
    commit.created(ids[j]);
  }
  auto resolve = [&](const FaceEntry& e) {
    return e.is_new ? face_ref(ids[ref_tet(e.ref)], ref_face(e.ref)) : e.ref;
  };
  for (std::size_t i = 0; i < faces.size(); i += 2)
    commit.link(resolve(faces[i]), resolve(faces[i + 1]));
  for (const TetId t : dying) commit.kill_without_history(t);
  for (const TetId t : ids) commit.born(t);
  stats.tetrahedra_removed = dying.size();
  stats.tetrahedra_created = created.size();
}

}  // namespace dtlab::engine
