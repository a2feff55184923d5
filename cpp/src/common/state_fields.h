// What the three state files (vof_state.cpp, dem_state.cpp, coupler_state.cpp) share: the checkpoint's
// map of named arrays, the look-up of one entry, the in-place copy, and the tables of a state's arrays.
// One table row per array (its checkpoint key, its member in the typed state, its member in the live
// object, its size) drives the export, the check, the import and both directions of the checkpoint.
#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/common/check.h"

namespace vofdem::state {

using StateMap = std::map<std::string, std::vector<double>>;
constexpr std::size_t kAnySize = static_cast<std::size_t>(-1);

// the entry `key` of a checkpoint, of `size` values (kAnySize: any)
inline const std::vector<double>& entry(const StateMap& s, const std::string& key, std::size_t size) {
  const auto it = s.find(key);
  if (it == s.end()) throw std::invalid_argument("state: missing entry '" + key + "'");
  if (size != kAnySize) require_size(key.c_str(), it->second, size);
  return it->second;
}

// a checkpoint written before the stones' arrays were named for what they hold ("disc_pos" for every
// stone shape, now "stone_pos"), with its keys renamed; `prefix` is the module's ("", "dem/", "coupler/").
// Returns s itself when it holds no such key (no copy)
inline const StateMap& with_stone_keys(const StateMap& s, const std::string& prefix, StateMap& renamed) {
  const std::string old = prefix + "disc_";
  bool legacy = false;
  for (const auto& kv : s) legacy = legacy || kv.first.rfind(old, 0) == 0;
  if (!legacy) return s;
  renamed.clear();
  for (const auto& kv : s)
    renamed[kv.first.rfind(old, 0) == 0 ? prefix + "stone_" + kv.first.substr(old.size()) : kv.first] = kv.second;
  return renamed;
}

// the contact pairs of a checkpoint (i[k], j[k]) of n stones: 0 <= i < j < n and sorted by (i, j); else
// std::invalid_argument naming `what` ("contact", "polygon contact", ...)
inline void check_sorted_pairs(const char* what, const std::vector<int>& i, const std::vector<int>& j, std::size_t n) {
  for (std::size_t k = 0; k < i.size(); ++k) {
    const bool sorted = k == 0 || i[k - 1] < i[k] || (i[k - 1] == i[k] && j[k - 1] < j[k]);
    if (!(i[k] >= 0 && i[k] < j[k] && j[k] < static_cast<int>(n)) || !sorted)
      throw std::invalid_argument("import_state: " + std::string(what) + " pair (" + std::to_string(i[k]) + ", " +
                                  std::to_string(j[k]) + ") is outside 0 <= i < j < n or not sorted by (i, j)");
  }
}

// same size: written in place, so the numpy views of dst stay valid; another size reallocates
template <class T>
void copy_into(std::vector<T>& dst, const std::vector<T>& src) {
  if (dst.size() == src.size()) std::copy(src.begin(), src.end(), dst.begin());
  else dst = src;
}

template <class T>
std::vector<double> to_double(const std::vector<T>& v) {
  return std::vector<double>(v.begin(), v.end());
}

template <class T>
void from_double(std::vector<T>& dst, const std::vector<double>& src) {
  dst.assign(src.size(), T{});
  for (std::size_t k = 0; k < src.size(); ++k) dst[k] = static_cast<T>(src[k]);
}

// one array of a state: `State::*state` is the copy's member, `Live::*live` the object's, `per` the
// values per item (cell, face, stone), `missing` what a checkpoint written before it existed holds
// (optional false: the entry is required)
template <class State, class Live, class T>
struct Field {
  const char* key;
  std::vector<T> State::*state;
  std::vector<T> Live::*live;
  int where;  // which count the size is a multiple of (the module's own enumeration)
  std::size_t per;
  bool optional;
  double missing;
};

}  // namespace vofdem::state

namespace vofdem {
class Grid2D;
struct FlowState;
namespace state {
// the flow's part of a checkpoint ("fluid/...", "turbulence/..."): moves the arrays of f into s, and
// back (entries added since are optional, with what older runs had)
void flow_to_map(FlowState& f, StateMap& s);
FlowState flow_from_map(const StateMap& s, const Grid2D& g);
}  // namespace state
}  // namespace vofdem
