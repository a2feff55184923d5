// Effect flags in Python: every solver's flags are an enum.IntFlag (py::native_enum), FlowEffect,
// DEMFlag and CouplerEffect; the older module constants (DEM_GRAVITY, COUPLE_TWO_WAY, ...) are the same
// members under their former names.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace vofdem::bind {

namespace py = pybind11;

// m.<prefix><NAME> = m.<enum_name>.<NAME> for every member of the (finalized) enum
inline void export_flag_members(py::module_& m, const char* enum_name, const std::string& prefix) {
  const py::object members = m.attr(enum_name).attr("__members__");
  for (py::handle name : members) m.attr((prefix + py::str(name).cast<std::string>()).c_str()) = members[name];
}

}  // namespace vofdem::bind
