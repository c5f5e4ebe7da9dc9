// The `gblens` Python module's shared parts (pybind11): the frame handle every array keeps alive,
// the exception that carries the CLI's one-line messages, JSON -> Python, a quantity decoded.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "views/capture/capture.h"

namespace gb::python {

namespace py = pybind11;

// gblens.Error: a user mistake or an unreadable input, with the message the CLI prints after
// "gblens COMMAND: " (a flag named there is named as the keyword argument: "fail=abc", not "--fail abc").
// Its subclasses say which: gblens.ArgumentError (also a ValueError) for an argument's value,
// gblens.QuantityError (also a KeyError) for a quantity the frame does not have.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct ArgumentError : Error {
  using Error::Error;
};
struct QuantityError : Error {
  using Error::Error;
};
[[noreturn]] inline void fail(const std::string& message) { throw Error(message); }
[[noreturn]] inline void failArgument(const std::string& message) { throw ArgumentError(message); }

// The engine's message with a leading CLI flag named as the keyword argument ("--fail abc: ..." ->
// "fail=abc: ..."); `flags` maps each flag to its argument ({"--fail", "fail"}).
std::string keywordMessage(const std::string& message, const std::vector<std::pair<std::string, std::string>>& flags);

// A frame with what a capture records about it; shared by the Python Frame and every array that
// points into it (their base is a capsule holding a reference), so arrays outlive the Frame safely.
struct FrameHandle {
  Capture capture;   // dir: the capture folder, or what made the frame ("render builtin:temple")
  CaptureMeta meta;  // for Frame.save
};
using FramePtr = std::shared_ptr<FrameHandle>;

// A numpy array over memory `owner` keeps alive (no copy).
template <class Owner>
py::array view(const py::dtype& dtype, std::vector<py::ssize_t> shape, const void* data, std::shared_ptr<Owner> owner) {
  auto* keep = new std::shared_ptr<Owner>(std::move(owner));
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
  return py::array(dtype, std::move(shape), {}, data, base);
}
// A numpy array taking over a vector's memory (no copy).
template <class T>
py::array adopt(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto owned = std::make_shared<std::vector<T>>(std::move(values));
  const T* data = owned->data();
  return view(py::dtype::of<T>(), std::move(shape), data, std::move(owned));
}

py::object toPython(const nlohmann::json& j);

// A Frame, or a path opened as a capture (compare's arguments).
FramePtr frameOf(const py::object& frameOrPath);
FramePtr openCapture(const std::string& dir);

// A quantity decoded as Frame[name] gives it: float64 values and their shape, (H, W) for a scalar,
// (H, W, C) otherwise (QuantityError: no quantity of that name; Error: its target is not held).
struct Decoded {
  std::vector<double> values;
  std::vector<py::ssize_t> shape;
};
Decoded decodeQuantity(const FramePtr& frame, const std::string& name);
// The numpy type of a stored target's texels (Frame.targets).
py::dtype dtypeOfPixels(PixelType type);

void bindFrame(py::module_& m);
void bindCompare(py::module_& m);
void bindRender(py::module_& m);
void bindSequence(py::module_& m);

}  // namespace gb::python
