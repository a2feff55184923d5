// Clump stones in the 3D packing generator (stone_packing.h, weir_packing_3d.h).
//
// Each stone draws, from a second generator seeded from the weir's seed (the diameters and the lattice's
// jitter follow the same draws as for spheres), one shape of the mix WeirSpec::clump with equal chances,
// scaled to the drawn nominal diameter d (its union's volume pi d^3 / 6, clump.h), and an orientation
// uniform over the rotations (Shoemake 1992: from u1, u2, u3 uniform in [0, 1),
//   q = (sqrt(1 - u1) sin 2 pi u2, sqrt(1 - u1) cos 2 pi u2, sqrt(u1) sin 2 pi u3, sqrt(u1) cos 2 pi u3),
// a unit quaternion uniform on the 3-sphere). The pour's lattice is spaced by the stones' real extent (the
// mix's largest intermediate length, about d, not the bounding diameter of 1.3-1.5 d) and a site is free
// where the stone's sub-spheres clear every placed stone's (fits_3d); the rounds settle at a low friction,
// a light compaction, before the weir's friction returns (pour_friction). Measured on the C++ tests' small
// weir over seeds 0-4 (benchmarks/results/clump_weir_packing.md): porosity 0.76-0.79 -> 0.63-0.65 by the
// lattice and sub-sphere test, -> 0.58 with the compaction; outline error 1.16-1.46 d -> 0.79-0.94 d. The
// bottom layer keeps bounding-sphere spacing. The library shapes
// are integrated once, at d = 1, and scaled (Clump::scaled), so a weir of hundreds of stones costs three
// integrations. The porosity samples the stones' sub-spheres on a 3D point grid (weir_porosity_3d_spheres),
// independent of any flow grid.
//
// Reference: Shoemake, K. (1992), Uniform random rotations, Graphics Gems III, 124-132.
#include "stones/clump_packing.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stones/packing_random.h"
#include "vofdem/common/numbers.h"
#include "vofdem/stones/clump.h"
#include "vofdem/stones/clump_model.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/weir_packing_3d.h"

namespace vofdem {

namespace {
using packing_random::uniform01;

class ClumpPacking final : public StonePacking {
 public:
  explicit ClumpPacking(const WeirSpec& s) : rng_(s.seed ^ 0xc3a5c85c97cb3127ull), mix_(s.clump) {
    check_clump_mix(mix_);
    for (const std::string& name : mix_.names) {
      unit_.push_back(quarried_stone(name, 1.0, mix_.ratio_intermediate, mix_.ratio_short));
      factor_ = std::max(factor_, 2.0 * unit_.back().bounding_radius());
      lattice_ = std::max(lattice_, unit_.back().principal_extents()[1]);
    }
  }

  // shape data: (index of the mix's shape, nominal diameter [m])
  PackedStone draw(double d) override {
    PackedStone out;
    const std::size_t k = std::min(unit_.size() - 1, static_cast<std::size_t>(uniform01(rng_) * unit_.size()));
    const double u1 = uniform01(rng_), u2 = uniform01(rng_), u3 = uniform01(rng_);
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    out.quat = {a * std::sin(2.0 * kPi * u2), a * std::cos(2.0 * kPi * u2), b * std::sin(2.0 * kPi * u3),
                b * std::cos(2.0 * kPi * u3)};
    out.shape = {static_cast<double>(k), d};
    out.radius = unit_[k].scaled(d).bounding_radius();
    return out;
  }

  double bounding_factor() const override { return factor_; }

  // the pour lattice from the stones' real extent: the largest intermediate length of the mix (1.0-1.03 d
  // for the library's 1 : 0.8 : 0.6) instead of the bounding diameter (1.3-1.5 d); a site is taken only
  // where the stone's sub-spheres clear those of every placed stone (fits_3d), so a long stone turned
  // towards a neighbour waits for a later round
  double lattice_factor() const override { return lattice_; }

  bool fits_3d(const PackedStones& pile, double x, double y, double z, const PackedStone& s,
               double margin) const override {
    const Eigen::Vector3d at(x, y, z);
    const std::vector<Eigen::Vector4d> mine = world_spheres(at, s.quat.data(), s.shape);
    for (std::size_t i = 0; i < pile.size(); ++i) {
      const Eigen::Vector3d c(pile.pos[2 * i], pile.y[i], pile.pos[2 * i + 1]);
      if ((c - at).norm() > pile.radius[i] + s.radius + margin) continue;
      for (const Eigen::Vector4d& b : world_spheres(c, &pile.quat[4 * i], pile.shape[i]))
        for (const Eigen::Vector4d& a : mine)
          if ((a.head<3>() - b.head<3>()).norm() <= a[3] + b[3] + margin) return false;
    }
    return true;
  }

  // a light compaction, as a laboratory tamps a dumped weir: the rounds settle at this stone-stone friction,
  // the stones slide into the hollows the lattice left, then the weir's own friction returns for a last
  // settling inside the slope walls (weir_packing_3d.cpp)
  double pour_friction() const override { return kPourFriction; }

  // settled clumps block the lattice's sites sooner than spheres do: with the lattice of bounding diameters
  // the rounds added 35, 23, 21, 18, 13, 9, 9, 5, 5, 2, 2, 3, then 0-2 at the Maeno weir across 0.2 m (the
  // first 12 brought 181 of the 186 stones of 24 rounds); the rounds stop early when one adds no stone
  int pour_rounds() const override { return kRounds; }

  // a stone that left the outline at a toe is not the weir's, whatever its shape
  bool drop_toe_rollers() const override { return true; }

  DEMSystem make(const DEMParams& p, const PackedStones& pile, double density) const override {
    if (pile.y.size() != pile.size() || pile.quat.size() != 4 * pile.size())
      throw std::invalid_argument("clump packing: every stone needs its y and quaternion");
    std::vector<Clump> clumps;
    clumps.reserve(pile.size());
    for (const std::vector<double>& s : pile.shape)
      clumps.push_back(unit_.at(static_cast<std::size_t>(s.at(0))).scaled(s.at(1)));
    DEMSystem sys(p, pile.pos, pile.radius, {density}, pile.fixed);
    set_clumps(sys, clumps);
    sys.stone_y = pile.y;
    sys.stone_quat = pile.quat;
    return sys;
  }

  // the sub-spheres of the active stones, in the world, sampled on a 3D point grid
  double porosity_3d(const DEMSystem& sys, const WeirSpec& spec) const override {
    const auto* model = dynamic_cast<const ClumpModel*>(&sys.model());
    if (!model) throw std::logic_error("clump packing: the system's model is not the clump model");
    const std::vector<double>& body = model->spheres();
    const std::vector<int>& offset = model->offsets();
    std::vector<double> world;
    for (int i = 0; i < sys.n(); ++i) {
      if (!sys.stone_active[i]) continue;
      const double* q = &sys.stone_quat[4 * i];
      const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
      const Eigen::Vector3d x(sys.stone_pos[2 * i], sys.stone_y[i], sys.stone_pos[2 * i + 1]);
      for (int g = offset[i]; g < offset[i + 1]; ++g) {
        const Eigen::Vector3d c = x + r * Eigen::Vector3d(body[4 * g], body[4 * g + 1], body[4 * g + 2]);
        world.insert(world.end(), {c[0], c[1], c[2], body[4 * g + 3]});
      }
    }
    return weir_porosity_3d_spheres(world, sys.params().width, spec);
  }

 private:
  std::mt19937_64 rng_;
  ClumpMix mix_;
  std::vector<Clump> unit_;  // the mix's shapes at d = 1, principal frames
  double factor_ = 1.0;      // the largest bounding diameter over the nominal one [-]
  double lattice_ = 0.0;     // the largest intermediate length over the nominal diameter [-]
  static constexpr int kRounds = 12;
  static constexpr double kPourFriction = 0.1;  // [-]

  // the sub-spheres (centre, radius) [m] in the world of shape (k, d) at x turned by q (w, x, y, z)
  std::vector<Eigen::Vector4d> world_spheres(const Eigen::Vector3d& x, const double* q,
                                             const std::vector<double>& shape) const {
    const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    const double d = shape.at(1);
    std::vector<Eigen::Vector4d> out;
    for (const ClumpSphere& c : unit_.at(static_cast<std::size_t>(shape.at(0))).spheres()) {
      const Eigen::Vector3d w = x + r * (d * c.centre);
      out.emplace_back(w[0], w[1], w[2], d * c.radius);
    }
    return out;
  }
};
}  // namespace

std::unique_ptr<StonePacking> make_clump_packing(const WeirSpec& spec) { return std::make_unique<ClumpPacking>(spec); }

}  // namespace vofdem
