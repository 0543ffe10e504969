#include "dtlab/predicates/audit.hpp"

#include <cstdio>

namespace dtlab::predicates {

const char* stage_name(Stage s) {
  switch (s) {
    case Stage::A:
      return "A";
    case Stage::B:
      return "B";
    case Stage::C:
      return "C";
    case Stage::D:
      return "D";
    case Stage::Gmp:
      return "gmp";
  }
  return "?";
}

const char* predicate_name(Predicate p) {
  switch (p) {
    case Predicate::Orient3d:
      return "orient3d";
    case Predicate::Insphere:
      return "insphere";
    case Predicate::Orient2d:
      return "orient2d";
    case Predicate::IncircleLifted:
      return "incircle_lifted";
  }
  return "?";
}

void AuditCounters::reset() {
  for (auto& row : by_stage) {
    for (auto& v : row) v.store(0, std::memory_order_relaxed);
  }
  for (auto& v : calls) v.store(0, std::memory_order_relaxed);
  for (auto& v : wrong_sign) v.store(0, std::memory_order_relaxed);
}

AuditCounters& audit_counters() {
  static AuditCounters counters;
  return counters;
}

// Stage A is the busiest column, so it is wider.
std::string audit_table(const char* kernel_name) {
  const AuditCounters& c = audit_counters();
  std::string out;
  char cell[64];
  std::snprintf(cell, sizeof cell, "%-16s %-9s %14s", "predicate", "kernel", "calls");
  out += cell;
  for (int s = 0; s < kStageCount; ++s) {
    const std::string name = std::string("stage ") + stage_name(static_cast<Stage>(s));
    std::snprintf(cell, sizeof cell, " %*s", s == 0 ? 14 : 12, name.c_str());
    out += cell;
  }
  std::snprintf(cell, sizeof cell, " %12s\n", "wrong sign");
  out += cell;
  for (int p = 0; p < kPredicateCount; ++p) {
    std::snprintf(cell, sizeof cell, "%-16s %-9s %14llu", predicate_name(static_cast<Predicate>(p)),
                  kernel_name, static_cast<unsigned long long>(c.calls[p].load()));
    out += cell;
    for (int s = 0; s < kStageCount; ++s) {
      std::snprintf(cell, sizeof cell, " %*llu", s == 0 ? 14 : 12,
                    static_cast<unsigned long long>(c.by_stage[p][s].load()));
      out += cell;
    }
    std::snprintf(cell, sizeof cell, " %12llu\n",
                  static_cast<unsigned long long>(c.wrong_sign[p].load()));
    out += cell;
  }
  return out;
}

}  // namespace dtlab::predicates
