#pragma once
// The studies of `dtlab experiment`, one file each.
#include "../study.hpp"
#include "../summary.hpp"

namespace dtlab::experiments {

Study burglary_errors_study();
Study predicate_errors_study();
Study speedup_study();
Study breakdown_study();
Study flips_study();
Study deadlocks_study();
Study hull_loss_study();
Study compare_study();
Study peers_study();
// The tools the peers study knows (--tools), in its column order.
std::vector<std::string> peers_study_tools();

}  // namespace dtlab::experiments
