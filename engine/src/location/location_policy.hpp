#pragma once
// The location mode (--location) resolved into the four decisions it bundles, once per run:
// every part of the engine reads the part it depends on, never the mode itself, so that a future
// mode can combine the parts differently (a new Location value and one case below).
//   order       how the points are ordered for insertion (insertion_order.hpp), and whether they
//               are stored in that order (the BRIO order renumbers the vertices)
//   locator     how a point is found (point_location.hpp): the history DAG's descent from the
//               roots, or a visibility walk from the last insertion
//   history     the store keeps DAG children: dead tetrahedra are the DAG's inner nodes, and a
//               replacement writes its new tetrahedra as their children
//   slot_reuse  dead slots are reused (once the epochs say no operation can reach them, on a
//               shared mesh); never with history, whose dead tetrahedra are still read
#include "dtlab/engine/options.hpp"

namespace dtlab::engine {

enum class InsertionOrder { Random, BrioHilbert };
enum class Locator { DagDescent, Walk };

struct LocationPolicy {
  InsertionOrder order = InsertionOrder::Random;
  Locator locator = Locator::DagDescent;
  bool history = true;
  bool slot_reuse = false;
};

constexpr LocationPolicy resolve_location(Location location) {
  switch (location) {
    case Location::Walk:
      return {InsertionOrder::BrioHilbert, Locator::Walk, false, true};
    case Location::Dag:
      break;
  }
  return {InsertionOrder::Random, Locator::DagDescent, true, false};
}

}  // namespace dtlab::engine
