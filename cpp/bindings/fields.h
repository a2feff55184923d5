// Properties of a parameter struct, each one line: a field with its docstring ending with its default,
// and a field of one of its parts: the k-epsilon settings most runs touch (FlowParams.turbulence_cfl ->
// turbulence.cfl) and the older names of the medium's fields (FlowParams.rho_water -> medium.rho_water).
#pragma once

#include <pybind11/pybind11.h>

#include <charconv>
#include <cstddef>
#include <string>
#include <type_traits>

namespace vofdem::bind {

namespace py = pybind11;

// a value as Python prints it: the shortest text that reads back the same double, True/False, an enum's
// member name (its enum bound before)
template <class T>
std::string default_text(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return v ? "True" : "False";
  } else if constexpr (std::is_enum_v<T>) {
    return py::str(py::cast(v).attr("name"));
  } else if constexpr (std::is_floating_point_v<T>) {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
    return std::string(buf, end);
  } else {
    return std::to_string(v);
  }
}

// a field's docstring ending with the default-constructed struct's value: the default is written once, in
// its header, and the text follows it
template <class P, class T>
std::string with_default(const std::string& doc, T P::*field) {
  return doc + ", default " + default_text(P{}.*field);
}

// the same for a field of one of the struct's parts (FlowParams::turbulence.cfl)
template <class P, class Part, class T>
std::string with_default(const std::string& doc, Part P::*part, T Part::*field) {
  return doc + ", default " + default_text(P{}.*part.*field);
}

// P.name <-> P::field, the docstring ending with the default (with_default)
template <class P, class T, class... Options>
void def_field(py::class_<P, Options...>& cls, const char* name, T P::*field, const std::string& doc) {
  cls.def_readwrite(name, field, with_default(doc, field).c_str());
}

// P.name <-> P::part.field
template <class P, class Part, class T, class... Options>
void def_part_field(py::class_<P, Options...>& cls, const char* name, Part P::*part, T Part::*field,
                    const std::string& doc) {
  cls.def_property(
      name, [part, field](const P& p) { return (p.*part).*field; },
      [part, field](P& p, const T& v) { (p.*part).*field = v; }, doc.c_str());
}

// P.name <-> P::part.field, the docstring ending with the default
template <class P, class Part, class T, class... Options>
void def_part_default(py::class_<P, Options...>& cls, const char* name, Part P::*part, T Part::*field,
                      const std::string& doc) {
  def_part_field(cls, name, part, field, with_default(doc, part, field));
}

// P.name <-> P::part.field[index] (one element of an array field)
template <class P, class Part, class A, class... Options>
void def_part_element(py::class_<P, Options...>& cls, const char* name, Part P::*part, A Part::*field, std::size_t index,
                      const std::string& doc) {
  cls.def_property(
      name, [part, field, index](const P& p) { return ((p.*part).*field)[index]; },
      [part, field, index](P& p, double v) { ((p.*part).*field)[index] = v; }, doc.c_str());
}

}  // namespace vofdem::bind
