// hull-loss: the paper's auxiliary tetrahedron against dtlab's vertex at infinity: the hull
// tetrahedra the auxiliary tetrahedron's vertices keep out of the mesh, per family and size.
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    for (const engine::Bounding bounding : {engine::Bounding::Infinite, engine::Bounding::AuxTet}) {
      RunSpec spec = base;
      spec.options.bounding = bounding;
      spec.variant = engine::to_string(bounding);
      spec.validate = true;
      runs.push_back(spec);
    }
  });
  return runs;
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "location", "runs", "tetrahedra (infinite vertex)",
                       "tetrahedra (aux-tet)", "hull tetrahedra lost (mean / median / max)",
                       "lost %", "reflex boundary edges (aux-tet, median)", "infinite vertex valid",
                       "seconds (infinite vertex)", "seconds (aux-tet)"});
  const auto groups =
      group_rows(t, {"input", "size_asked", "location"}, [&](const Row& r) { return is_ok(t, r); });
  for (const RowGroup& g : groups) {
    std::vector<const Row*> infinite;
    std::vector<const Row*> aux;
    for (const Row* r : g.rows) (t.get(*r, "bounding") == "aux-tet" ? aux : infinite).push_back(r);
    const double full = aggregate_of(t, infinite, "tetrahedra").mean;
    const Aggregate lost = aggregate_of(t, aux, "hull_tetrahedra_lost");
    std::size_t valid = 0;
    for (const Row* r : infinite) valid += t.get(*r, "validation.valid") == "true" ? 1 : 0;
    table.add({g.key[0], thousands(aggregate_of(t, g.rows, "points").median), g.key[2],
               std::to_string(aux.size()), thousands(full),
               thousands(aggregate_of(t, aux, "tetrahedra").mean), mean_median_max(lost),
               fixed(100.0 * lost.mean / full, 3),
               fixed(aggregate_of(t, aux, "validation.reflex_boundary_edges").median, 0),
               std::to_string(valid) + " / " + std::to_string(infinite.size()),
               fixed(aggregate_of(t, infinite, "seconds.total").median, 3),
               fixed(aggregate_of(t, aux, "seconds.total").median, 3)});
  }
  return table.str() +
         "\n\"hull tetrahedra lost\" is measured by the engine in aux-tet mode: Delaunay "
         "tetrahedra of the points that the auxiliary tetrahedron's far vertices keep out of the "
         "mesh (removing them leaves a non-convex boundary: the validator's reflex boundary "
         "edges). The infinite vertex loses none; its meshes must all be valid.\n";
}

}  // namespace

Study hull_loss_study() {
  return {"hull-loss",
          "hull tetrahedra lost by the paper's auxiliary tetrahedron, against the vertex at "
          "infinity",
          {3,
           1,
           {},
           {},
           {1000, 10000, 100000},
           {1000},
           {"uniform", "normal", "cluster", "grid", "sphere", "bunny_zipper"},
           {"uniform", "sphere"},
           {engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
