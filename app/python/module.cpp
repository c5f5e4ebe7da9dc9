// The `gblens` Python module (docs/python.md): frames from captures, imports and the renderer, their
// targets and decoded quantities as numpy arrays, the probe, statistics, check, compare and its report;
// sequences as arrays with a time axis, their motion vectors checked, flicker.
#include "app/python/python.h"

namespace gb::python {

std::string keywordMessage(const std::string& message, const std::vector<std::pair<std::string, std::string>>& flags) {
  for (const auto& [flag, keyword] : flags)
    if (message.rfind(flag + " ", 0) == 0) return keyword + "=" + message.substr(flag.size() + 1);
    else if (message.rfind(flag + ":", 0) == 0) return keyword + message.substr(flag.size());
  return message;
}

py::object toPython(const nlohmann::json& j) {
  // One exact conversion: JSON text through Python's own parser (gblens's JSON writes no NaN).
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace gb::python

PYBIND11_MODULE(gblens, m) {
  namespace py = pybind11;
  m.doc() = R"(gblens: G-buffer frames as numpy arrays, decoded by their layout.

Frames come from captures and imports (``open``) or the headless renderer (``render``); each holds its
stored targets (``Frame.targets``) and decodes its quantities (``Frame[name]``); ``Frame.probe``,
``Frame.stats`` and ``Frame.check`` are the CLI's commands, ``compare`` compares two frames;
``open_sequence`` opens a sequence (frames, and arrays with a time axis), ``motion`` and ``flicker``
analyse one. Every error is a ``gblens.Error``. See docs/python.md.)";
  m.attr("__version__") = GBLENS_VERSION;
  // Docstrings carry their own signatures (app/python/docstrings.h): inspect.signature reads them.
  py::options options;
  options.disable_function_signatures();
  static py::exception<gb::python::Error> error(m, "Error", PyExc_RuntimeError);
  error.attr("__doc__") = "A user mistake or an unreadable input, with the one line the CLI prints (flags named as keywords).";
  static py::exception<gb::python::ArgumentError> argument(m, "ArgumentError", py::make_tuple(error, py::handle(PyExc_ValueError)));
  argument.attr("__doc__") = "An argument's value gblens cannot use; the message starts with the keyword (\"rect=...\").";
  static py::exception<gb::python::QuantityError> quantity(m, "QuantityError", py::make_tuple(error, py::handle(PyExc_KeyError)));
  quantity.attr("__doc__") = "A quantity the frame does not have (Frame[name], Frame.quantity); also a KeyError.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gb::python::QuantityError& e) {
      quantity(e.what());
    } catch (const gb::python::ArgumentError& e) {
      argument(e.what());
    } catch (const gb::python::Error& e) {
      error(e.what());
    }
  });
  gb::python::bindFrame(m);
  gb::python::bindCompare(m);
  gb::python::bindRender(m);
  gb::python::bindSequence(m);
}
