// Zero-copy numpy views of C++ arrays.
//
// A view's base is the Python object that owns the C++ object, so the owner lives as long as any view
// of its memory (as MuJoCo's bindings do).
//
// The rule: an array behind a view keeps its buffer for the owner's lifetime. Setting parameters,
// building or freeing a Coupler, stepping, a guard's restore and importing a state or checkpoint of
// the same sizes write into the arrays in place (never swap, move or reassign a vector of another
// size). Only a call that changes a size reallocates, and its docstring says that it invalidates
// earlier views: DEMSystem.resize, DEMSystem.set_polygons (the poly_* arrays), DEMSystem.import_state
// or set_state of another stone or vertex count, VofBoundaryInflow.resize and the assignment of a
// whole side of it (the views of that side). tests/test_views.py holds every view of VOFGrid,
// DEMSystem and Coupler across those calls; tests/cpp/common/test_buffer_stability.cpp checks the same
// buffers under the sanitizers.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace vofdem::bind {

namespace py = pybind11;

// 1-D view of `data` of length n, owned by `owner`
template <class T>
py::array_t<T> view(T* data, py::ssize_t n, py::handle owner) {
  return py::array_t<T>({n}, {static_cast<py::ssize_t>(sizeof(T))}, data, owner);
}

template <class T>
py::array_t<T> view(std::vector<T>& v, py::handle owner) {
  return view(v.data(), static_cast<py::ssize_t>(v.size()), owner);
}

// read-only 1-D view
template <class T>
py::array_t<T> const_view(const std::vector<T>& v, py::handle owner) {
  auto a = view(const_cast<T*>(v.data()), static_cast<py::ssize_t>(v.size()), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// 2-D row-major view (rows, cols) of a flat array, e.g. a field (nz, nx) or positions (n, 2)
template <class T>
py::array_t<T> view2d(T* data, py::ssize_t rows, py::ssize_t cols, py::handle owner) {
  const auto s = static_cast<py::ssize_t>(sizeof(T));
  return py::array_t<T>({rows, cols}, {cols * s, s}, data, owner);
}

// (n, 2) view of an interleaved (x, z) per-stone array of length 2n
template <class T>
py::array_t<T> view_pairs(std::vector<T>& v, py::handle owner) {
  return view2d(v.data(), static_cast<py::ssize_t>(v.size() / 2), 2, owner);
}

}  // namespace vofdem::bind
