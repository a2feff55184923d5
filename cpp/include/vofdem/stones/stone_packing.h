// How a stone model's stones are drawn and placed by the weir's packing generator (weir_packing.h).
//
// The generator owns the procedure (bottom row, pours on a loose lattice, settling, trimming, stones laid
// into hollows) and asks the model's StonePacking for what depends on the shape: a stone of nominal
// diameter d (its bounding radius, orientation and body-frame shape), the fixed bottom row, whether a
// stone fits at a point, and how the placed stones become a DEMSystem of that model. A model that can be
// packed returns one from StoneModel::packing(); the generator never asks which model it holds.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace vofdem {

class DEMSystem;
struct DEMParams;
struct WeirSpec;

// a stone drawn for the packing: its bounding radius [m], orientation [rad] and the model's body-frame
// shape data (empty for a disc); 3D stones: its orientation as a unit quaternion (w, x, y, z)
struct PackedStone {
  double radius = 0.0;
  double angle = 0.0;
  std::vector<double> shape{};
  std::array<double, 4> quat{{1.0, 0.0, 0.0, 0.0}};
};

// the stones placed so far: centres (x, z) [m], bounding radii [m], orientations [rad], fixed flags and
// shapes, one entry each; for 3D models (weir_packing_3d.h) also the centres across the flume y [m] and
// the orientations as unit quaternions (w, x, y, z), 4 each (empty in the plane)
struct PackedStones {
  std::vector<double> pos, radius, angle;
  std::vector<std::uint8_t> fixed;
  std::vector<std::vector<double>> shape;
  std::vector<double> y, quat;
  void add(double x, double z, const PackedStone& s, std::uint8_t fixed_flag);
  // a 3D stone at (x, y, z), turned by s.quat
  void add(double x, double y, double z, const PackedStone& s, std::uint8_t fixed_flag);
  // stone i of sys, whose shape is that of `from`'s stone i
  void copy_stone(const DEMSystem& sys, const PackedStones& from, int i);
  // the positions and orientations of sys (the same stones, settled)
  void take(const DEMSystem& sys);
  std::size_t size() const { return radius.size(); }
};

class StonePacking {
 public:
  virtual ~StonePacking() = default;
  // a stone of nominal diameter d [m] (its shape and orientation from the model's own generator)
  virtual PackedStone draw(double d) = 0;
  // the largest bounding diameter over the nominal one [-]: the pour lattice's pitch
  virtual double bounding_factor() const { return 1.0; }
  // the fixed bottom row on the bed along the base [x_toe, x_end], touching stones whose nominal
  // diameters come from next_diameter() (2D models: the 3D generator lays its own bottom layer and
  // tests fits with bounding spheres, so the default throws std::logic_error)
  virtual void bottom_row(const WeirSpec& spec, const std::function<double()>& next_diameter, PackedStones& pile);
  // whether stone s at (x, z) keeps more than margin [m] from every placed stone (2D models; the default
  // throws std::logic_error)
  virtual bool fits(const PackedStones& pile, double x, double z, const PackedStone& s, double margin) const;
  // orientations tried, a sixth of a turn apart, where a stone is laid by hand into a hollow
  virtual int turns() const { return 1; }
  // 3D models: the most rounds of the pour (each refills the room the settling left; they stop when one
  // adds no stone)
  virtual int pour_rounds() const { return 6; }
  // whether stones that rolled off a toe onto the bed are removed at the end (shapes that roll far)
  virtual bool drop_toe_rollers() const { return false; }
  // 3D models: the pour lattice's pitch over the largest nominal diameter [-] (the default: bounding_factor(),
  // sites as far apart as the largest bounding spheres)
  virtual double lattice_factor() const { return bounding_factor(); }
  // 3D models: whether stone s at (x, y, z) [m] keeps more than margin [m] from every placed stone (the
  // default: from their bounding spheres)
  virtual bool fits_3d(const PackedStones& pile, double x, double y, double z, const PackedStone& s,
                       double margin) const;
  // 3D models: the stone-stone friction [-] of the pour's rounds, a light compaction (the weir's own friction
  // returns for a last settling before the trim); negative: the weir's own throughout. WeirSpec::compaction_friction,
  // when set, replaces it
  virtual double pour_friction() const { return -1.0; }
  // the DEM system of the placed stones (radii, density, fixed flags; the model and its shapes; for 3D
  // models their y and quaternions)
  virtual DEMSystem make(const DEMParams& p, const PackedStones& pile, double density) const = 0;
  // 3D models: the porosity [-] of the packed weir's prism across the width (the default:
  // weir_porosity_3d, from the model's footprint)
  virtual double porosity_3d(const DEMSystem& sys, const WeirSpec& spec) const;
};

}  // namespace vofdem
