// The partitioned method (after Marot, Pellerin and Remacle 2019; docs/design.md, "The
// partitioned method"): no lock on the hot path. Each pass lays a Hilbert curve through a cube
// moved against the points and cuts it into one arc a thread (CurvePartition): two arcs are the
// curve's halves, laid to be slabs on either side of a plane across one axis, the axes taking
// turns; more are cut at the keys' quantiles. A thread inserts the pass's points of its arc along
// the curve, and an insertion that would change a tetrahedron with a vertex of another part, or
// whose walk would leave the tetrahedra no other thread writes, is given up (PartitionSync) and
// waits for the next pass, whose cuts lie elsewhere. So a thread reads nothing another writes: no
// epochs, and its dead slots are reused at once. The passes follow the BRIO rounds of the walk
// mode's order; a round's pass ends when its first part is done, and the points the others have
// not tried wait for the next pass. What is left after the last round goes in by further passes,
// the last ones on one thread. Walk mode only: the passes change the insertion order, which the
// DAG's expected cost rests on.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "location/insertion_order.hpp"
#include "methods/curve_partition.hpp"
#include "methods/kernel_dispatch.hpp"
#include "methods/method_input.hpp"
#include "methods/parallel_run.hpp"
#include "methods/partition_sync.hpp"
#include "methods/pass_curve.hpp"
#include "support/parallel_ranges.hpp"
#include "support/populate_pages.hpp"
#include "support/radix_sort.hpp"

namespace dtlab::engine {
namespace {

// Passes after the last round that may still use several parts, besides one for each halving of
// their parts (run()); then one part inserts the rest.
constexpr int kFinalParallelPasses = 3;
// Keys sampled to place the cuts.
constexpr std::size_t kCutSample = 4096;
// Two parts are slabs on either side of a plane across one axis: the least boundary that halves a
// box, so the fewest insertions cross it (uniform:1000000, 2 threads: about 49,000 points
// postponed against 90,000 with arcs cut at any key). The pass's curve is laid so that its two
// halves are the slabs (next_slab_axis, cut), so each part is still one arc. More parts are arcs
// cut at the keys' quantiles: P slabs would meet at P - 1 planes.
constexpr bool kSlabs = true;
// The least spread of the sampled points across a slabs' axis, in cells of the pass curve's grid.
constexpr double kSlabCells = 8;
// Tetrahedra looked at around an anchor point for a readable start (place_walk_starts).
constexpr std::size_t kStartSearch = 4096;
// A part's anchors: every this many of its pending points in a pass (place_walk_starts). Arcs'
// walks stop at their border (an arc leaves the points' box and comes back elsewhere), and
// their next walks need a start beyond it; a slab is convex, and no walk stopped at a slab's
// border in any input measured (uniform:1000000, grid:1000000, sphere:100000, dragon_vrip),
// so slabs have a quarter of the anchors (their setups 12 ms shorter at 1M uniform points;
// performance-log.md, sixteenth session).
constexpr std::size_t kArcAnchorSpacing = 256;
constexpr std::size_t kSlabAnchorSpacing = 1024;

// A part gets at least options.points_per_part points: in smaller passes the parts are small,
// most insertions cross a cut, and one thread is faster.
int parts_for(std::size_t points, const TriangulateOptions& options) {
  const std::size_t most = static_cast<std::size_t>(std::clamp(options.threads, 1, 255));
  const std::size_t per_part = std::max<std::size_t>(1, options.points_per_part);
  return static_cast<int>(std::clamp<std::size_t>(points / per_part, 1, most));
}

// The walk mode's BRIO rounds as ranges of `order` positions, first round first: [m/2, m),
// [m/4, m/2), ..., and a first round of at most kFirstRound points (insertion_order.hpp).
std::vector<std::pair<std::size_t, std::size_t>> brio_rounds(std::size_t m) {
  std::vector<std::pair<std::size_t, std::size_t>> rounds;
  std::size_t end = m;
  while (end > 0) {
    const std::size_t begin = end <= kFirstRound ? 0 : end / 2;
    rounds.emplace_back(begin, end);
    end = begin;
  }
  std::reverse(rounds.begin(), rounds.end());
  return rounds;
}

// Pass k's curve (PassCurve): its cube twice the input's, its corner moved back on each axis by a
// fraction of the input's side, in whole cells of the curve's grid (the fractions a
// low-discrepancy sequence: the additive recurrence by the reciprocals of the plastic number's
// powers, so that successive passes move the curve's coarse cell faces, where the arcs meet, to
// new places through the points). The grid, 512 cells across the input, is fine enough to cut
// and order points that spread through their box (512^3 cells, over a hundred a point at 1M);
// points crowded into a few cells (a far outlier) share keys, so the cuts fall unevenly and the
// passes are unbalanced: slower, never wrong (a part is any set of points).
std::array<std::uint32_t, 3> pass_shift(int k) {
  constexpr double kStep[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};
  std::array<std::uint32_t, 3> shift{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double fraction = std::fmod(0.5 + kStep[a] * k, 1.0);
    shift[a] = std::min(PassCurve::kInputCells - 1,
                        static_cast<std::uint32_t>(fraction * PassCurve::kInputCells));
  }
  return shift;
}

// A BRIO round's pass, whose points are a random sample of the input's and which a later pass
// always follows; or one of the passes after the last round, whose points are those given up or
// deferred before (pass()).
enum class PassKind { Round, Final };

template <class K>
class PartitionedRun {
 public:
  explicit PartitionedRun(const MethodInput& input, TriangulationStats& stats)
      : run_(input, stats, std::max(1, input.options.threads), /*lock_words=*/false),
        part_of_(input.points.size(), 0),
        failed_(static_cast<std::size_t>(run_.threads)),
        deferred_(static_cast<std::size_t>(run_.threads)),
        stopped_walks_(static_cast<std::size_t>(run_.threads), 0),
        busy_(static_cast<std::size_t>(run_.threads), 0.0),
        unlocated_(static_cast<std::size_t>(run_.threads)),
        anchors_(static_cast<std::size_t>(run_.threads)) {
    for (int i = 0; i < run_.threads; ++i) {
      syncs_.push_back(std::make_unique<PartitionSync>(run_.mesh, part_of_));
      inserters_.push_back(std::make_unique<ThreadInserter<K, PartitionSync>>(
          run_, i, run_.thread_stats(i), *syncs_.back()));
    }
  }

  std::vector<Tetrahedron> run() {
    std::vector<std::uint32_t> carried;  // postponed and deferred points, for the next pass
    const auto rounds = brio_rounds(run_.order.size());  // none when only the first four points
    if (!rounds.empty()) {
      last_round_begin_ = rounds.back().first;
      // The sort buffers' size while they are kept: the last round's points and an eighth more
      // for the points carried into its pass (about 3 % at 1M uniform points, 2 threads).
      sort_buffer_size_ = (rounds.back().second - rounds.back().first) * 9 / 8;
    }
    for (const auto& [begin, end] : rounds) {
      std::vector<std::uint32_t> pending(run_.order.begin() + static_cast<std::ptrdiff_t>(begin),
                                         run_.order.begin() + static_cast<std::ptrdiff_t>(end));
      append_in_order(pending, carried);
      carried = pass(pending, begin, parts_for(pending.size(), run_.options), PassKind::Round);
    }
    // After a pass that gave up a third of its points or more, the next has half its parts: the
    // points left lie where the parts met (at 16 parts their borders hold about a quarter of a
    // part's points), and fewer parts have less border; or they are the hull's, whose cavities
    // spread over its flat faces, which some cut crosses whatever the curve: two parts halve to
    // one. (Going to one thread at once left it an eighth of uniform:1000000 and a third of
    // dragon_vrip at 16 threads: performance-log.md, eighteenth session.)
    int most_parts = run_.threads;
    int halvings = 0;
    for (int final_pass = 0; !carried.empty(); ++final_pass) {
      const int parts = final_pass < kFinalParallelPasses + halvings
                            ? std::min(most_parts, parts_for(carried.size(), run_.options))
                            : 1;
      std::vector<std::uint32_t> pending;
      append_in_order(pending, carried);
      carried = pass(pending, run_.order.size(), parts, PassKind::Final);
      const PartitionPass& last = run_.stats.partition_passes.back();
      if (parts > 1 && 3 * last.postponed >= last.points) {
        most_parts = parts / 2;
        ++halvings;
      }
    }
    for (int i = 0; i < run_.threads; ++i) {
      run_.finish_thread(i, inserters_[static_cast<std::size_t>(i)]->dt);
    }
    curve_.release();
    return run_.output(run_.finish());
  }

 private:
  // The postponed points after the pending ones, in insertion order (the walk mode's: along the
  // curve within each round; they are few: a sort).
  void append_in_order(std::vector<std::uint32_t>& pending, std::vector<std::uint32_t>& postponed) {
    std::sort(postponed.begin(), postponed.end());
    pending.insert(pending.end(), postponed.begin(), postponed.end());
    postponed.clear();
  }

  // Inserts `pending` on `parts` threads; the vertices so far are the first four and those of
  // order[0, vertices_end) not pending. Returns the points postponed (given up) and, in a round's
  // pass, those deferred: once one part has tried all its points, the others stop and leave
  // the points they have not tried to the next pass, which spreads them over every thread,
  // instead of idle threads waiting for the slowest (the parts' work differs, and so do the cores'
  // speeds on a shared machine). The passes after the rounds run to their end: deferring there
  // too often left a few thousand points to the one-thread pass, and the runs were no faster
  // (performance-log.md, fifteenth session).
  std::vector<std::uint32_t> pass(std::vector<std::uint32_t>& pending, std::size_t vertices_end,
                                  int parts, PassKind kind) {
    const auto start = std::chrono::steady_clock::now();
    // A hint, read between insertions; the step's start and end (the pool's, or the threads'
    // start and join: support/worker_pool.hpp) order everything else.
    first_part_done_.store(false, std::memory_order_relaxed);
    const bool defers = kind == PassKind::Round && parts > 1;
    // A round's points are a sample of the input's, so the input's quantiles split them evenly;
    // the points after the rounds crowd where earlier parts met or where a part stopped.
    cut(parts, vertices_end, kind == PassKind::Round ? nullptr : &pending);
    // The rounds' passes before the last reuse one pair of sort buffers (mapping fresh pages for
    // each pass cost nearly as much as its sort); the last round's pass frees them after its
    // sort, so that they do not add to the run's peak, which comes later.
    if (parts > 1) {
      sort_along_pass_curve(pending, kind == PassKind::Round && vertices_end < last_round_begin_);
    }
    for (int i = 0; i < run_.threads; ++i) {
      syncs_[static_cast<std::size_t>(i)]->set_part(static_cast<std::uint8_t>(i), parts == 1);
    }
    if (parts > 1) place_walk_starts(parts, pending);
    const auto threads_start = std::chrono::steady_clock::now();
    run_.on_threads([&](int i) {
      if (i >= parts) return;
      const auto thread_start = std::chrono::steady_clock::now();
      insert_part(i, parts, pending, defers);
      busy_[static_cast<std::size_t>(i)] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - thread_start).count();
    });
    std::vector<std::uint32_t> carried;
    for (auto& f : failed_) {
      carried.insert(carried.end(), f.begin(), f.end());
      f.clear();
    }
    PartitionPass record;
    record.postponed = carried.size();
    for (auto& d : deferred_) {
      carried.insert(carried.end(), d.begin(), d.end());
      d.clear();
    }
    record.deferred = carried.size() - record.postponed;
    for (std::uint64_t& stopped : stopped_walks_) {
      record.stopped_walks += stopped;
      stopped = 0;
    }
    record.points = pending.size();
    record.parts = static_cast<std::uint64_t>(parts);
    record.after_rounds = kind == PassKind::Final;
    record.cut_axis = parts > 1 ? slab_axis_ : -1;
    record.most_points = parts > 1 ? most_points_ : pending.size();
    record.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    record.setup_seconds = std::chrono::duration<double>(threads_start - start).count();
    double most = 0;
    double sum = 0;
    for (int i = 0; i < parts; ++i) {
      most = std::max(most, busy_[static_cast<std::size_t>(i)]);
      sum += busy_[static_cast<std::size_t>(i)];
    }
    record.imbalance = sum > 0 ? most / (sum / parts) : 1.0;
    run_.stats.partition_passes.push_back(record);
    return carried;
  }

  // A pass cut along a curve inserts along it: each part's points are then one run, so that a
  // thread walks from each point to the next, not across the other parts between its runs of the
  // walk mode's order (an arc is not convex). The keys also name the pending points' parts.
  void sort_along_pass_curve(std::vector<std::uint32_t>& pending, bool keep_buffers) {
    if (sort_keyed_.size() < pending.size()) {
      const std::size_t size =
          keep_buffers ? std::max(pending.size(), sort_buffer_size_) : pending.size();
      sort_keyed_ = {};  // freed before the larger pair is mapped
      sort_scratch_ = {};
      sort_keyed_ = populated_vector<KeyedId>(size, run_.threads);
      sort_scratch_ = populated_vector<KeyedId>(size, run_.threads);
    }
    KeyedId* const keyed = sort_keyed_.data();
    in_parallel_ranges(
        pending.size(), run_.threads, [&](std::size_t begin, std::size_t end, std::size_t) {
          for (std::size_t i = begin; i < end; ++i) {
            const std::uint64_t key = pass_key(pending[i]);
            part_of_[pending[i]] = static_cast<std::uint8_t>(partition_.part_of(key));
            keyed[i] = {key, pending[i]};
          }
        });
    stable_sort_by_key(keyed, sort_scratch_.data(), pending.size(), run_.threads);
    for (std::size_t i = 0; i < pending.size(); ++i) pending[i] = keyed[i].second;
    if (!keep_buffers) {
      sort_keyed_ = {};
      sort_scratch_ = {};
    }
  }

  // Lays the pass's curve (moved by pass_shift; for two parts centred across next_slab_axis on
  // the sampled points' median, in an orientation that fills the half below first, and cut in
  // the middle: slabs), cuts it and names the parts of the vertices so far (pass() names the
  // pending points' as it sorts them). Cutting one curve at other places would not do: the arcs
  // of one curve meet along the faces of its coarse cells whatever the cuts, and the points
  // postponed there would be postponed again. The points sampled are `from`'s, or all the points
  // when `from` is null: a BRIO round is a random sample of them, so its parts get as many points.
  // The points after the rounds are not: the deferred ones lie together where a part stopped,
  // and with the input's quantiles one part got most of them (uniform:1000000, 2 threads, arcs,
  // the first pass after the rounds: imbalance up to 1.35 against at most 1.08 with theirs, and
  // no more points postponed; performance-log.md, thirteenth session).
  void cut(int parts, std::size_t vertices_end, const std::vector<std::uint32_t>* from) {
    if (parts == 1) {
      partition_.cut({}, 1);
      return;
    }
    std::vector<std::uint32_t> sampled;
    const std::size_t count = from ? from->size() : run_.input.input_count;
    const std::size_t step = std::max<std::size_t>(1, count / kCutSample);
    for (std::size_t i = 0; i < count; i += step) {
      sampled.push_back(from ? (*from)[i] : static_cast<std::uint32_t>(i));
    }
    if (!curve_.has_cells()) {  // the first pass of several parts
      const auto& points = run_.input.points;
      curve_.find_cells(points, hilbert_frame(points, run_.input.input_count, run_.threads),
                        run_.threads);
    }
    std::array<std::uint32_t, 3> shift = pass_shift(++curves_laid_);
    slab_axis_ = parts == 2 && kSlabs ? next_slab_axis(sampled) : -1;
    if (slab_axis_ >= 0) {
      last_slab_axis_ = slab_axis_;
      // The curve's halves are the two sides of the grid's face nearest the sampled points'
      // median across the axis: slabs, each one arc.
      std::vector<double> c(sampled.size());
      for (std::size_t i = 0; i < sampled.size(); ++i) c[i] = coordinate(sampled[i], slab_axis_);
      const auto middle = c.begin() + static_cast<std::ptrdiff_t>(c.size() / 2);
      std::nth_element(c.begin(), middle, c.end());
      curve_.lay_halves(shift, slab_axis_, curve_.nearest_face(*middle, slab_axis_));
      partition_.cut_at(PassCurve::kHalfKey);
    } else {
      curve_.move(shift);
      std::vector<std::uint64_t> sample;
      sample.reserve(sampled.size());
      for (const std::uint32_t v : sampled) sample.push_back(pass_key(v));
      std::sort(sample.begin(), sample.end());
      partition_.cut(sample, parts);
    }
    const std::vector<std::uint32_t>& order = run_.order;
    in_parallel_ranges(vertices_end, run_.threads,
                       [&](std::size_t begin, std::size_t end, std::size_t) {
                         for (std::size_t i = begin; i < end; ++i) {
                           part_of_[order[i]] = name_part(order[i]);
                         }
                       });
    for (const std::uint32_t v : run_.input.first) part_of_[v] = name_part(v);
  }
  // The axis this pass's slabs are cut across, or -1 for arcs cut at the keys' quantiles. Never
  // the axis of the pass before (whose postponed points lie at its plane, and a plane across the
  // same axis at the same quantile would meet them again), and only an axis along which the
  // sampled points spread at least half as far as along the widest and over kSlabCells cells of
  // the grid (between their 5 % and 95 % quantiles: a far outlier does not count): a plane across
  // a thin axis would cut through all of a flat input, and one inside a single layer of cells
  // would not halve it. The axes take turns from the last slabs' axis; a long, thin input, with
  // one such axis, has slabs every other pass and arcs cut at the quantiles between.
  int next_slab_axis(const std::vector<std::uint32_t>& sampled) const {
    std::array<double, 3> spread{};
    if (sampled.size() >= 2) {
      std::vector<double> c(sampled.size());
      const auto low = static_cast<std::ptrdiff_t>(sampled.size() / 20);
      const auto high = static_cast<std::ptrdiff_t>(sampled.size() - 1) - low;
      for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t i = 0; i < sampled.size(); ++i) {
          c[i] = coordinate(sampled[i], static_cast<int>(a));
        }
        std::nth_element(c.begin(), c.begin() + low, c.end());
        const double below = c[static_cast<std::size_t>(low)];
        std::nth_element(c.begin(), c.begin() + high, c.end());
        spread[a] = c[static_cast<std::size_t>(high)] - below;
      }
    }
    const double widest = std::max({spread[0], spread[1], spread[2]});
    const int turn_from = slab_axis_ >= 0 ? slab_axis_ : last_slab_axis_;
    for (int step = 1; step <= 3; ++step) {
      const int a = (turn_from + step) % 3;
      const double along = spread[static_cast<std::size_t>(a)];
      if (a != slab_axis_ && 2 * along >= widest && curve_.cells_in(along) >= kSlabCells) return a;
    }
    return -1;
  }
  // Before a pass of several parts, each part on its own thread: the walk starts of the part at its
  // anchors, every kArcAnchorSpacing-th (kSlabAnchorSpacing-th for slabs) of its pending points
  // (the first included), each a
  // tetrahedron with a vertex of the part (readable: no other thread writes it in the pass), the
  // nearest found to the anchor point. The walks to these points may go anywhere now, as nobody
  // writes. A part's first walk starts at its first anchor; a later anchor's start is taken after
  // a give-up (insert_part), so that a walk stopped at the part's border (where an arc leaves
  // the points' box and comes back elsewhere, or a slab's points come near its plane, say) does
  // not leave every later walk of the pass
  // starting there. An anchor with no readable tetrahedron near it (none in kStartSearch) has
  // none: the part's points after it wait for the next anchor or pass.
  void place_walk_starts(int parts, const std::vector<std::uint32_t>& pending) {
    std::vector<std::size_t> counted(static_cast<std::size_t>(parts), 0);
    const std::size_t spacing = slab_axis_ >= 0 ? kSlabAnchorSpacing : kArcAnchorSpacing;
    for (auto& a : anchors_) a.clear();
    for (std::size_t position = 0; position < pending.size(); ++position) {
      const std::uint8_t part = part_of_[pending[position]];
      if (counted[part]++ % spacing == 0) anchors_[part].push_back({position, kNoTet});
    }
    most_points_ = *std::max_element(counted.begin(), counted.end());
    // Each part's walks on its own thread: they only read, and nobody writes until they end.
    run_.on_threads([&](int i) {
      const auto index = static_cast<std::size_t>(i);
      if (i >= parts || anchors_[index].empty()) return;
      PartitionSync& sync = *syncs_[index];
      auto& dt = inserters_[index]->dt;
      sync.set_part(static_cast<std::uint8_t>(i), true);
      for (Anchor& a : anchors_[index]) {
        a.start = dt.locate_only(pending[a.position]);  // walks on from the last one
        dt.end_operation();
      }
      sync.set_part(static_cast<std::uint8_t>(i), false);
      for (Anchor& a : anchors_[index]) a.start = readable_near(a.start, sync);
      dt.set_walk_start(anchors_[index].front().start);
    });
  }
  // A tetrahedron `sync` may read: t or the nearest in a breadth-first search over faces.
  TetId readable_near(TetId t, const PartitionSync& sync) const {
    const TetStore& tets = run_.mesh.tets;
    if (t == kNoTet || sync.readable(tets[t])) return t;  // mostly: no search
    std::vector<TetId> queue{t};
    std::unordered_set<TetId> seen{t};
    for (std::size_t i = 0; i < queue.size() && i < kStartSearch; ++i) {
      const Tet& tet = tets[queue[i]];
      if (sync.readable(tet)) return queue[i];
      for (const FaceRef r : tet.neighbor) {
        if (seen.insert(ref_tet(r)).second) queue.push_back(ref_tet(r));
      }
    }
    return kNoTet;
  }

  // Vertex v's part in this pass; for slabs from its cell across their axis, without its key.
  std::uint8_t name_part(std::uint32_t v) const {
    if (slab_axis_ >= 0) return curve_.in_second_half(v) ? 1 : 0;
    return static_cast<std::uint8_t>(partition_.part_of(pass_key(v)));
  }
  // Point v's position along the pass's curve.
  std::uint64_t pass_key(std::uint32_t v) const { return curve_.key(v); }
  double coordinate(std::uint32_t v, int axis) const {
    return predicates::coordinate(run_.input.points[v], axis);
  }

  // Thread i's share of the pass: the pending points of its part, in the pass's order; after a
  // give-up the walks go on from the next anchor (place_walk_starts). With `defers`, the part
  // that inserts its last point first ends the pass for the others (pass()).
  void insert_part(int i, int parts, const std::vector<std::uint32_t>& pending, bool defers) {
    const auto index = static_cast<std::size_t>(i);
    ThreadStats counters;  // added to stats.threads once (optimistic_worker.hpp says why)
    auto& dt = inserters_[index]->dt;
    std::vector<std::uint32_t>& failed = failed_[index];
    using Outcome = typename IncrementalDelaunay<K, PartitionSync>::Outcome;
    const std::vector<Anchor>& anchors = anchors_[index];
    std::size_t next_anchor = 1;  // the first one is the pass's first start
    bool gave_up = false;         // since the last anchor
    std::size_t tried = 0;        // of the part's points
    std::size_t position = 0;
    for (; position < pending.size(); ++position) {
      const std::uint32_t v = pending[position];
      if (parts > 1 && part_of_[v] != i) continue;
      if (run_.stopping()) break;
      if (defers && first_part_done_.load(std::memory_order_relaxed)) break;
      ++tried;
      if (parts > 1 && next_anchor < anchors.size() && anchors[next_anchor].position == position) {
        const TetId start = anchors[next_anchor++].start;
        // Readable, so written by this thread alone: its aliveness can be asked.
        if (gave_up && start != kNoTet && run_.mesh.tets.is_alive(start)) dt.set_walk_start(start);
        gave_up = false;
      }
      const Outcome outcome = dt.insert(v);
      // An abandoned insertion (the flip bound) may have killed the walk's start: the next
      // anchor's start is taken then too.
      gave_up = gave_up || outcome == Outcome::GaveUp || outcome == Outcome::Unlocated ||
                outcome == Outcome::Abandoned;
      count_outcome(outcome, counters);
      if (outcome == Outcome::Unlocated) {
        // A thread's walk reads only what nobody else changes, so a walk that failed (not one
        // stopped at the part's border, which gives up) is an inexact kernel's contradiction,
        // which repeats; a point is given a bounded number of tries (as in the lock methods).
        if (++unlocated_[index][v] > WorkSource::kMaxLocationAttempts) {
          ++counters.abandoned;
          run_.progressed(i);
          continue;
        }
      }
      if (outcome == Outcome::GaveUp || outcome == Outcome::Unlocated) {
        failed.push_back(v);
        if (outcome == Outcome::GaveUp && dt.walk_stopped()) ++stopped_walks_[index];
      } else {
        run_.progressed(i);
      }
    }
    if (position == pending.size()) {
      // A part with few points (keys crowded by a far outlier cut unevenly, or none at all) or
      // that gave up on most of them (walks stopped at its border) has not done its share of the
      // pass: ending it then would defer nearly everything.
      const bool did_its_share = 2 * static_cast<std::size_t>(parts) * tried >= pending.size() &&
                                 counters.inserted + counters.duplicates > failed.size();
      if (defers && did_its_share) first_part_done_.store(true, std::memory_order_relaxed);
    } else if (!run_.stopping()) {
      std::vector<std::uint32_t>& deferred = deferred_[index];
      for (; position < pending.size(); ++position) {
        if (part_of_[pending[position]] == i) deferred.push_back(pending[position]);
      }
    }
    // The counters this method's insertions touch (count_outcome's and the abandonments).
    ThreadStats& total = run_.stats.threads[index];
    total.inserted += counters.inserted;
    total.duplicates += counters.duplicates;
    total.abandoned += counters.abandoned;
    total.give_ups += counters.give_ups;
  }

  ParallelRun<K> run_;
  PassCurve curve_;                    // the current pass's curve
  std::vector<std::uint8_t> part_of_;  // each vertex's part in the current pass
  CurvePartition partition_;
  int curves_laid_ = 0;          // passes of several parts so far
  int slab_axis_ = -1;           // the slabs' axis (0 x, 1 y, 2 z) of this pass (or of the last of
                                 // several parts), or -1: arcs cut at the keys' quantiles
  int last_slab_axis_ = -1;      // of the last pass cut into slabs
  std::size_t most_points_ = 0;  // this pass: the most pending points a part has
  std::size_t last_round_begin_ = 0;  // the last BRIO round's first position in the order
  std::size_t sort_buffer_size_ = 0;  // the sort buffers' size while the rounds keep them
  std::vector<KeyedId> sort_keyed_;   // the pass's (key, point) pairs, sorted
  std::vector<KeyedId> sort_scratch_;
  std::vector<std::unique_ptr<PartitionSync>> syncs_;
  std::vector<std::unique_ptr<ThreadInserter<K, PartitionSync>>> inserters_;
  std::vector<std::vector<std::uint32_t>> failed_;    // per thread, this pass
  std::vector<std::vector<std::uint32_t>> deferred_;  // per thread, this pass: not tried
  std::atomic<bool> first_part_done_{false};          // this pass: a part tried all its points
  std::vector<std::uint64_t> stopped_walks_;          // per thread, this pass
  std::vector<double> busy_;                          // per thread, this pass's seconds
  std::vector<std::unordered_map<std::uint32_t, int>> unlocated_;  // per thread: failed walks
  struct Anchor {
    std::size_t position;  // in the pass's pending points
    TetId start;           // readable, near that point; kNoTet if none was found
  };
  std::vector<std::vector<Anchor>> anchors_;  // per part, this pass
};

}  // namespace

std::vector<Tetrahedron> run_partitioned(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() {
    PartitionedRun<K> run(input, stats);
    return run.run();
  });
}

}  // namespace dtlab::engine
