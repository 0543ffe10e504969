#pragma once
// Audit layer: a kernel wrapper that counts calls per predicate and per stage (adaptive: A, B, C,
// D, gmp; filtered: A, D, gmp), and for the fast kernel, how many signs differ from the exact
// kernel. It is a separate kernel type, so
// the choice is made at compile time and the plain kernels pay nothing.
#include <array>
#include <atomic>
#include <cstdint>
#include <string>

#include "dtlab/predicates/kernels.hpp"

namespace dtlab::predicates {

enum class Predicate : std::uint8_t {
  Orient3d = 0,
  Insphere = 1,
  Orient2d = 2,
  IncircleLifted = 3
};
inline constexpr int kPredicateCount = 4;
const char* predicate_name(Predicate p);

// Process-wide counters (relaxed atomics: they are statistics, no ordering is implied).
struct AuditCounters {
  std::array<std::array<std::atomic<std::uint64_t>, kStageCount>, kPredicateCount> by_stage{};
  std::array<std::atomic<std::uint64_t>, kPredicateCount> calls{};
  std::array<std::atomic<std::uint64_t>, kPredicateCount> wrong_sign{};
  void reset();
};
AuditCounters& audit_counters();

// Counts the calls of any kernel, the stages of a staged kernel (adaptive, filtered: those with
// *_staged functions), and for the others the calls whose sign differs from ExactKernel
// (evaluating both; nonzero only for `fast`).
template <class K>
struct Audited {
  static constexpr const char* kName = K::kName;
  static void count(Predicate p, int stage) {
    auto& c = audit_counters();
    c.calls[static_cast<int>(p)].fetch_add(1, std::memory_order_relaxed);
    if (stage >= 0) c.by_stage[static_cast<int>(p)][stage].fetch_add(1, std::memory_order_relaxed);
  }
  static void compare(Predicate p, int got, int exact) {
    if (got != exact) {
      audit_counters().wrong_sign[static_cast<int>(p)].fetch_add(1, std::memory_order_relaxed);
    }
  }
  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    if constexpr (requires { K::orient3d_staged(a, b, c, d); }) {
      const StagedSign s = K::orient3d_staged(a, b, c, d);
      count(Predicate::Orient3d, static_cast<int>(s.stage));
      return s.sign;
    } else {
      const int s = K::orient3d(a, b, c, d);
      count(Predicate::Orient3d, -1);
      compare(Predicate::Orient3d, s, ExactKernel::orient3d(a, b, c, d));
      return s;
    }
  }
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e) {
    if constexpr (requires { K::insphere_staged(a, b, c, d, e); }) {
      const StagedSign s = K::insphere_staged(a, b, c, d, e);
      count(Predicate::Insphere, static_cast<int>(s.stage));
      return s.sign;
    } else {
      const int s = K::insphere(a, b, c, d, e);
      count(Predicate::Insphere, -1);
      compare(Predicate::Insphere, s, ExactKernel::insphere(a, b, c, d, e));
      return s;
    }
  }
  // Counted as an orient3d call.
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v) {
    if constexpr (requires { K::orient3d_centroid_staged(a, b, c, v); }) {
      const StagedSign s = K::orient3d_centroid_staged(a, b, c, v);
      count(Predicate::Orient3d, static_cast<int>(s.stage));
      return s.sign;
    } else {
      const int s = K::orient3d_centroid(a, b, c, v);
      count(Predicate::Orient3d, -1);
      compare(Predicate::Orient3d, s, ExactKernel::orient3d_centroid(a, b, c, v));
      return s;
    }
  }
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
    if constexpr (requires { K::orient2d_staged(a, b, c, drop); }) {
      const StagedSign s = K::orient2d_staged(a, b, c, drop);
      count(Predicate::Orient2d, static_cast<int>(s.stage));
      return s.sign;
    } else {
      const int s = K::orient2d(a, b, c, drop);
      count(Predicate::Orient2d, -1);
      compare(Predicate::Orient2d, s, ExactKernel::orient2d(a, b, c, drop));
      return s;
    }
  }
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop) {
    if constexpr (requires { K::incircle_lifted_staged(a, b, c, d, drop); }) {
      const StagedSign s = K::incircle_lifted_staged(a, b, c, d, drop);
      count(Predicate::IncircleLifted, static_cast<int>(s.stage));
      return s.sign;
    } else {
      const int s = K::incircle_lifted(a, b, c, d, drop);
      count(Predicate::IncircleLifted, -1);
      compare(Predicate::IncircleLifted, s, ExactKernel::incircle_lifted(a, b, c, d, drop));
      return s;
    }
  }
};

// The audit table as text: one row per predicate; calls, one column per stage (A, B, C, D, gmp),
// wrong sign.
std::string audit_table(const char* kernel_name);

}  // namespace dtlab::predicates
