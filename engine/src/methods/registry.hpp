#pragma once
// The registry's internal side: the function that runs a method (its public side, the names and
// what each supports, is dtlab/engine/methods.hpp).
#include "dtlab/engine/options.hpp"
#include "methods/method_input.hpp"

namespace dtlab::engine {

MethodRun method_run(Method method);

}  // namespace dtlab::engine
