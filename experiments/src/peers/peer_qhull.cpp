// Qhull's Delaunay triangulation (the lower hull of the points lifted to the paraboloid), through
// its reentrant C library, in-process. Its tetrahedra are not oriented; a point Qhull leaves out
// (a duplicate, a point it merges) is simply not a vertex.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "peer_tools.hpp"

#ifdef DTLAB_HAS_QHULL
extern "C" {
#include <libqhull_r/libqhull_r.h>
}
#endif

namespace dtlab::experiments {

std::string qhull_version() {
#ifdef DTLAB_HAS_QHULL
  return std::string("Qhull ") + qh_version;
#else
  return "";
#endif
}

bool qhull_available() {
#ifdef DTLAB_HAS_QHULL
  return true;
#else
  return false;
#endif
}

#ifdef DTLAB_HAS_QHULL
namespace {

// Qhull's messages go to a FILE; this one collects them in memory.
class MessageFile {
 public:
  MessageFile() : file_(open_memstream(&text_, &size_)) {}
  ~MessageFile() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(text_);
  }
  MessageFile(const MessageFile&) = delete;
  MessageFile& operator=(const MessageFile&) = delete;
  FILE* get() const { return file_; }
  // The first line that names a Qhull message (QH6154 ...), else the first line.
  std::string first_message() {
    std::fflush(file_);
    const std::string all = text_ != nullptr ? std::string(text_, size_) : std::string();
    std::size_t at = all.find("QH");
    if (at == std::string::npos) at = 0;
    const std::size_t end = all.find('\n', at);
    return all.substr(at, end == std::string::npos ? std::string::npos : end - at);
  }

 private:
  char* text_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_;
};

// Frees everything Qhull allocated, however the run ended.
struct QhullSession {
  qhT state{};
  explicit QhullSession(FILE* errors) { qh_zero(&state, errors); }
  ~QhullSession() {
    qh_freeqhull(&state, !qh_ALL);
    int still_long = 0;
    int total_long = 0;
    qh_memfreeshort(&state, &still_long, &total_long);
  }
  QhullSession(const QhullSession&) = delete;
  QhullSession& operator=(const QhullSession&) = delete;
};

}  // namespace

PeerMesh run_qhull_peer(const std::vector<predicates::Point3>& points, const char* options) {
  if (points.size() > static_cast<std::size_t>(INT32_MAX / 3)) {
    throw PeerRefused("Qhull takes at most 2^31 / 3 points");
  }
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const auto& p : points) coordinates.insert(coordinates.end(), {p.x, p.y, p.z});
  MessageFile errors;
  QhullSession session(errors.get());
  qhT* qh = &session.state;
  std::string command = std::string("qhull ") + options;
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(),
                                     False, command.data(), nullptr, errors.get());
  if (exit_code != qh_ERRnone) {
    throw PeerRefused("Qhull exit code " + std::to_string(exit_code) + ": " +
                      errors.first_message());
  }
  PeerMesh mesh;
  mesh.oriented = false;
  facetT* facet = nullptr;
  FORALLfacets {
    if (facet->upperdelaunay) continue;
    engine::Tetrahedron tet{};
    int corner = 0;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(facet->vertices) {
      if (corner < 4)
        tet[static_cast<std::size_t>(corner)] =
            static_cast<std::uint32_t>(qh_pointid(qh, vertex->point));
      ++corner;
    }
    // A facet of the triangulated output has four vertices; a merged one (without Qt) may not.
    if (corner != 4) {
      throw PeerRefused("Qhull returned a Delaunay facet with " + std::to_string(corner) +
                        " vertices (not a tetrahedron)");
    }
    mesh.tetrahedra.push_back(tet);
  }
  return mesh;
}

#else

PeerMesh run_qhull_peer(const std::vector<predicates::Point3>& /*points*/,
                        const char* /*options*/) {
  throw std::runtime_error("this build has no Qhull (libqhull-dev: scripts/setup.sh)");
}

#endif

}  // namespace dtlab::experiments
