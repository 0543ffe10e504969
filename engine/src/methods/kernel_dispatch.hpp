#pragma once
// The predicate kernel chosen at compile time from the run's options: every method instantiates
// its run once per kernel (and its audited twin, which counts each call's stage) through
// with_kernel, so that the kernel's calls inline into the insertion loops.
#include "dtlab/engine/options.hpp"
#include "dtlab/predicates/audit.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::engine {

// f.template operator()<K>() for the kernel of `options` (audited with options.audit).
template <class F>
decltype(auto) with_kernel(const TriangulateOptions& options, F&& f) {
  auto run = [&]<class K>() -> decltype(auto) {
    if (options.audit) return f.template operator()<predicates::Audited<K>>();
    return f.template operator()<K>();
  };
  switch (options.kernel) {
    case KernelKind::Fast:
      return run.template operator()<predicates::FastKernel>();
    case KernelKind::Filtered:
      return run.template operator()<predicates::FilteredKernel>();
    case KernelKind::Exact:
      return run.template operator()<predicates::ExactKernel>();
    case KernelKind::Adaptive:
      break;
  }
  return run.template operator()<predicates::AdaptiveKernel>();
}

// Every kernel the engine's templates are instantiated for, X(K) for each: the explicit
// instantiations of the templates that one file defines and others call (methods/burglary_post_check.cpp).
#define DTLAB_FOR_EACH_KERNEL(X)                     \
  X(predicates::FastKernel)                          \
  X(predicates::AdaptiveKernel)                      \
  X(predicates::FilteredKernel)                      \
  X(predicates::ExactKernel)                         \
  X(predicates::Audited<predicates::FastKernel>)     \
  X(predicates::Audited<predicates::AdaptiveKernel>) \
  X(predicates::Audited<predicates::FilteredKernel>) \
  X(predicates::Audited<predicates::ExactKernel>)

}  // namespace dtlab::engine
