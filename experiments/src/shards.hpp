#pragma once
// Studies sharded over machines: `--shard K/N` runs every N-th point set of the plan (its group of
// runs on the same source and seed) from the K-th, and
// `dtlab experiment merge` joins the shards' folders into one study (docs/experiments.md,
// "Sharded sweeps"). Every run's folder has plan.json: the study, its shard, the commit, the
// parameters that shape the plan, and the whole plan's keys, which the merge compares.
#include <string>
#include <vector>

#include "study.hpp"

namespace dtlab::experiments {

struct Shard {
  int index = 0;  // 1..count; 0 with count 0: not sharded
  int count = 0;
};

// "K/N" with 1 <= K <= N <= 100000; empty: not sharded. Throws std::invalid_argument.
Shard parse_shard(const std::string& text);

// `groups`: each planned run's point-set group (the unit a shard takes: group mod N = K - 1).
std::string plan_json(const std::string& study, const Shard& shard, const std::string& commit,
                      const StudyParams& params, const std::vector<std::string>& plan_keys,
                      const std::vector<int>& groups);

}  // namespace dtlab::experiments
