#include "dtlab/predicates/audit.hpp"

#include <cstdio>

namespace dtlab::predicates {

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

std::string audit_table(const char* kernel_name) {
  const AuditCounters& c = audit_counters();
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %-9s %14s %14s %12s %12s %12s %12s\n", "predicate",
                "kernel", "calls", "stage A", "stage B", "stage C", "stage D", "wrong sign");
  out += line;
  for (int p = 0; p < kPredicateCount; ++p) {
    std::snprintf(line, sizeof line, "%-16s %-9s %14llu %14llu %12llu %12llu %12llu %12llu\n",
                  predicate_name(static_cast<Predicate>(p)), kernel_name,
                  static_cast<unsigned long long>(c.calls[p].load()),
                  static_cast<unsigned long long>(c.by_stage[p][0].load()),
                  static_cast<unsigned long long>(c.by_stage[p][1].load()),
                  static_cast<unsigned long long>(c.by_stage[p][2].load()),
                  static_cast<unsigned long long>(c.by_stage[p][3].load()),
                  static_cast<unsigned long long>(c.wrong_sign[p].load()));
    out += line;
  }
  return out;
}

}  // namespace dtlab::predicates
