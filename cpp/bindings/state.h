// A solver's state in Python, bound the same way for VOFGrid, DEMSystem and Coupler: the typed copy
// (copy_state / set_state, a value to branch from) and the checkpoint (export_state / import_state, a
// dict of named numpy arrays).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace vofdem::bind {

namespace py = pybind11;

// a solver's whole state (export_state) as a dict of numpy arrays, copied: a checkpoint outlives the solver
using StateMap = std::map<std::string, std::vector<double>>;

inline py::dict state_to_dict(const StateMap& s) {
  py::dict d;
  for (const auto& [key, v] : s) {
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(double));
    d[py::str(key)] = a;
  }
  return d;
}

inline StateMap dict_to_state(const py::dict& d) {
  StateMap s;
  for (const auto& item : d) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(item.second);
    if (!a) throw py::value_error("state entry '" + py::str(item.first).cast<std::string>() + "' is not numeric");
    s[py::str(item.first).cast<std::string>()] = std::vector<double>(a.data(), a.data() + a.size());
  }
  return s;
}

// the typed state class: a value with its time [s] and step count readable
template <class State, class Steps>
void bind_state_class(py::module_& m, const char* name, const char* doc, const char* steps_name, Steps State::*steps) {
  py::class_<State>(m, name, doc)
      .def_readonly("time", &State::time, "simulated time [s]")
      .def_readonly(steps_name, steps, "steps taken since the start [-]");
}

// copy_state() / set_state(copy) of an Owner with export_state(State&) and import_state(const State&)
template <class State, class Owner, class... Options>
void def_copy_state(py::class_<Owner, Options...>& cls, const char* copy_doc, const char* set_doc) {
  cls.def(
         "copy_state",
         [](const Owner& o) {
           State s;
           o.export_state(s);
           return s;
         },
         copy_doc)
      .def("set_state", py::overload_cast<const State&>(&Owner::import_state), py::arg("state"), set_doc);
}

// export_state() / import_state(dict) of an Owner whose checkpoint is a map of named arrays
template <class Owner, class... Options>
void def_checkpoint_state(py::class_<Owner, Options...>& cls, const char* import_doc) {
  cls.def(
      "export_state", [](const Owner& o) { return state_to_dict(o.export_state()); },
      "the whole state as a dict of named numpy arrays, copied (a checkpoint; import_state(dict) restores it bit for bit)")
      .def("import_state", [](Owner& o, const py::dict& d) { o.import_state(dict_to_state(d)); }, py::arg("state"),
           import_doc);
}

}  // namespace vofdem::bind
