// Properties of a parameter struct that read and write a field of one of its parts: the k-epsilon
// settings most runs touch (FlowParams.turbulence_cfl -> turbulence.cfl) and the older names of the
// medium's fields (FlowParams.rho_water -> medium.rho_water), each one line.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>

namespace vofdem::bind {

namespace py = pybind11;

// P.name <-> P::part.field
template <class P, class Part, class T, class... Options>
void def_part_field(py::class_<P, Options...>& cls, const char* name, Part P::*part, T Part::*field, const char* doc) {
  cls.def_property(
      name, [part, field](const P& p) { return (p.*part).*field; },
      [part, field](P& p, const T& v) { (p.*part).*field = v; }, doc);
}

// P.name <-> P::part.field[index] (one element of an array field)
template <class P, class Part, class A, class... Options>
void def_part_element(py::class_<P, Options...>& cls, const char* name, Part P::*part, A Part::*field, std::size_t index,
                      const char* doc) {
  cls.def_property(
      name, [part, field, index](const P& p) { return ((p.*part).*field)[index]; },
      [part, field, index](P& p, double v) { ((p.*part).*field)[index] = v; }, doc);
}

}  // namespace vofdem::bind
