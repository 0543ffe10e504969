// dtlab._dtlab: the engine for Python. The public API, its argument checks and its documentation
// are in dtlab/__init__.py; this module takes arrays already shaped and typed. The engine's
// refusals of an input become ValueError with the CLI's message, a run that could not finish
// (watchdog, store limit) RuntimeError, a cancelled run KeyboardInterrupt.
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

#include "dtlab/common/build_info.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/io/input_error.hpp"

namespace dtlab::python {
namespace py = pybind11;
void bind_triangulate(py::module_& m);
void bind_mesh(py::module_& m);
void bind_predicates(py::module_& m);
}  // namespace dtlab::python

PYBIND11_MODULE(_dtlab, m) {
  namespace py = pybind11;
  m.doc() = "dtlab's engine (use the dtlab package, not this module)";
  m.attr("version") = dtlab::version();
  m.attr("commit") = dtlab::build_commit();
  py::register_local_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const dtlab::engine::RunCancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const dtlab::engine::RunFailed& e) {  // not the input's fault: the run's
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const dtlab::engine::TriangulationError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const dtlab::io::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  dtlab::python::bind_triangulate(m);
  dtlab::python::bind_mesh(m);
  dtlab::python::bind_predicates(m);
}
