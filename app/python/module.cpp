// The `gblens` Python module (docs/python.md): frames from captures, imports and the renderer, their
// targets and decoded quantities as numpy arrays, the probe, statistics, check, compare and its report.
#include "app/python/python.h"

namespace gb::python {

py::object toPython(const nlohmann::json& j) {
  // One exact conversion: JSON text through Python's own parser (gblens's JSON writes no NaN).
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace gb::python

PYBIND11_MODULE(gblens, m) {
  namespace py = pybind11;
  m.doc() = "gblens: G-buffer frames as numpy arrays, decoded by their layout; probe, stats, check, compare, report";
  py::register_exception<gb::python::Error>(m, "Error", PyExc_RuntimeError);
  gb::python::bindFrame(m);
  gb::python::bindCompare(m);
  gb::python::bindRender(m);
}
