// Hashes of a solver's exported state for the pinned tests (test_disc_pins.cpp, test_polygon_pins.cpp):
// FNV-1a over the keys and the bytes of every array, in the map's (sorted) order.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace vofdem::test {

// arrays that joined export_state() after the pins were taken: the rolling springs (contact_mr,
// wall_mr), the k-epsilon model's state (turbulence/...), the water level each stone's wet fraction
// follows (stone_water_level), the linearised drag handed to the DEM (stone_drag_coef, stone_drag_vel), and
// the fluid's boundary budget and time-scheme history (fluid/net_inflow_volume, prev_dt, face_u_prev,
// face_w_prev, dilatation_volume, last_advective). They are left out of the hash, so that it covers the
// same arrays as when the pins were taken; rolling_springs_zero() checks the springs.
inline bool added_after_pins(const std::string& key) {
  static const char* const kAdded[] = {"contact_mr",          "wall_mr",           "stone_water_level",
                                       "stone_drag_coef",     "stone_drag_vel",     "fluid/net_inflow_volume",
                                       "fluid/prev_dt",       "fluid/face_u_prev", "fluid/face_w_prev",
                                       "fluid/dilatation_volume", "fluid/last_advective"};
  const std::string k = key.rfind("dem/", 0) == 0 ? key.substr(4) : key;
  for (const char* a : kAdded)
    if (k == a) return true;
  return key.rfind("turbulence/", 0) == 0;
}

// true if the rolling springs hold only zeros (the rolling resistance off, as before it existed)
inline bool rolling_springs_zero(const std::map<std::string, std::vector<double>>& state) {
  for (const auto& [key, v] : state) {
    const std::string k = key.rfind("dem/", 0) == 0 ? key.substr(4) : key;
    if (k != "contact_mr" && k != "wall_mr") continue;
    for (double x : v)
      if (x != 0.0) return false;
  }
  return true;
}

// a key as named when the pins were taken: the stones' arrays were then "disc_pos" and the like for
// every stone shape ("dem/disc_pos", "coupler/disc_force_drag"); now "stone_pos"
inline std::string pinned_name(const std::string& key) {
  for (const char* prefix : {"", "dem/", "coupler/"}) {
    const std::string p = std::string(prefix) + "stone_";
    if (key.rfind(p, 0) == 0) return std::string(prefix) + "disc_" + key.substr(p.size());
  }
  return key;
}

// FNV-1a over the keys (as pinned_name() gives them, in their sorted order) and the bytes of the arrays
// of `state` that keep(key) accepts
template <class Keep>
std::uint64_t fnv_state(const std::map<std::string, std::vector<double>>& state, Keep keep) {
  std::map<std::string, const std::vector<double>*> named;
  for (const auto& [key, v] : state)
    if (keep(key)) named[pinned_name(key)] = &v;
  std::uint64_t h = 1469598103934665603ull;
  for (const auto& [key, pv] : named) {
    const std::vector<double>& v = *pv;
    for (char c : key) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t k = 0; k < v.size() * sizeof(double); ++k) h = (h ^ b[k]) * 1099511628211ull;
  }
  return h;
}

// every array (determinism and restart tests)
inline std::uint64_t state_hash(const std::map<std::string, std::vector<double>>& state) {
  return fnv_state(state, [](const std::string&) { return true; });
}

// the arrays the pins were taken over
inline std::uint64_t pin_hash(const std::map<std::string, std::vector<double>>& state) {
  return fnv_state(state, [](const std::string& key) { return !added_after_pins(key); });
}

}  // namespace vofdem::test
