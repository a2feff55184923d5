// Clump stones in the 3D packing generator (stone_packing.h, weir_packing_3d.h): see clump_packing.cpp.
#pragma once

#include <memory>

#include "vofdem/stones/stone_packing.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem {

// the packing of the spec's clump mix (WeirSpec::clump, checked: std::invalid_argument naming the field)
std::unique_ptr<StonePacking> make_clump_packing(const WeirSpec& spec);

}  // namespace vofdem
