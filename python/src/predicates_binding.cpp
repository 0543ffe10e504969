// dtlab._dtlab.orient3d / insphere over arrays of points: the sign of every row, and with
// `audit` the stage that decided it, so that a kernel can be measured on one's own data.
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "arrays.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::python {
namespace {

using predicates::Point3;
using predicates::Stage;
using predicates::StagedSign;

// The stage codes as Python sees them: the adaptive and filtered kernels' stages (kernels.hpp),
// then "float" for the fast kernel (no stage: the float determinant's sign, unchecked) and "gmp"
// for every call of the exact kernel.
constexpr std::uint8_t kFloatOnly = predicates::kStageCount;

const Point3* rows(const PointArray& a, py::ssize_t n, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3 || a.shape(0) != n) {
    throw std::invalid_argument(std::string(name) + " must be (n, 3) like the first argument");
  }
  return reinterpret_cast<const Point3*>(a.data());  // NOLINT: (n, 3) float64 rows are Point3s
}

template <int Arity>
py::tuple signs(const std::vector<PointArray>& args, const std::string& kernel) {
  const py::ssize_t n = args[0].ndim() == 2 ? args[0].shape(0) : -1;
  std::array<const Point3*, Arity> p{};
  for (int i = 0; i < Arity; ++i) {
    p[static_cast<std::size_t>(i)] = rows(args[static_cast<std::size_t>(i)], n,
                                          i == 0 ? "the first argument" : "every argument");
  }
  py::array_t<std::int8_t> sign(n);
  py::array_t<std::uint8_t> stage(n);
  std::int8_t* s = sign.mutable_data();
  std::uint8_t* g = stage.mutable_data();
  const auto call = [&](auto staged) {
    py::gil_scoped_release unlocked;
    for (py::ssize_t i = 0; i < n; ++i) {
      StagedSign r{};
      if constexpr (Arity == 4) {
        r = staged(p[0][i], p[1][i], p[2][i], p[3][i]);
      } else {
        r = staged(p[0][i], p[1][i], p[2][i], p[3][i], p[4][i]);
      }
      s[i] = static_cast<std::int8_t>(r.sign);
      g[i] = static_cast<std::uint8_t>(r.stage);
    }
  };
  using predicates::AdaptiveKernel;
  using predicates::ExactKernel;
  using predicates::FastKernel;
  using predicates::FilteredKernel;
  const auto with_stage = [](int sign, std::uint8_t code) {
    return StagedSign{sign, static_cast<Stage>(code)};
  };
  if (kernel == "adaptive") {
    call([](const auto&... q) {
      if constexpr (sizeof...(q) == 4)
        return AdaptiveKernel::orient3d_staged(q...);
      else
        return AdaptiveKernel::insphere_staged(q...);
    });
  } else if (kernel == "filtered") {
    call([](const auto&... q) {
      if constexpr (sizeof...(q) == 4)
        return FilteredKernel::orient3d_staged(q...);
      else
        return FilteredKernel::insphere_staged(q...);
    });
  } else if (kernel == "fast") {
    call([&](const auto&... q) {
      if constexpr (sizeof...(q) == 4)
        return with_stage(FastKernel::orient3d(q...), kFloatOnly);
      else
        return with_stage(FastKernel::insphere(q...), kFloatOnly);
    });
  } else if (kernel == "exact") {
    call([&](const auto&... q) {
      const auto gmp = static_cast<std::uint8_t>(Stage::Gmp);
      if constexpr (sizeof...(q) == 4)
        return with_stage(ExactKernel::orient3d(q...), gmp);
      else
        return with_stage(ExactKernel::insphere(q...), gmp);
    });
  } else {
    throw std::invalid_argument("kernel must be one of fast, adaptive, filtered, exact (got '" +
                                kernel + "')");
  }
  return py::make_tuple(sign, stage);
}

py::list stage_names() {
  py::list names;
  for (int s = 0; s < predicates::kStageCount; ++s) {
    names.append(std::string(predicates::stage_name(static_cast<Stage>(s))));
  }
  names.append("float");
  return names;
}

}  // namespace

void bind_predicates(py::module_& m) {
  m.def("orient3d", [](const PointArray& a, const PointArray& b, const PointArray& c,
                       const PointArray& d, const std::string& kernel) {
    return signs<4>({a, b, c, d}, kernel);
  });
  m.def("insphere", [](const PointArray& a, const PointArray& b, const PointArray& c,
                       const PointArray& d, const PointArray& e, const std::string& kernel) {
    return signs<5>({a, b, c, d, e}, kernel);
  });
  m.def("stage_names", &stage_names);
}

}  // namespace dtlab::python
