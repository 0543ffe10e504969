// The studies `dtlab experiment` knows, in the order --list prints them.
#include "studies/studies.hpp"

namespace dtlab::experiments {

const std::vector<Study>& all_studies() {
  static const std::vector<Study> studies = {burglary_errors_study(),
                                             predicate_errors_study(),
                                             speedup_study(),
                                             breakdown_study(),
                                             flips_study(),
                                             deadlocks_study(),
                                             hull_loss_study(),
                                             compare_study(),
                                             peers_study()};
  return studies;
}

const Study* find_study(const std::string& name) {
  for (const Study& s : all_studies()) {
    if (name == s.name) return &s;
  }
  return nullptr;
}

}  // namespace dtlab::experiments
