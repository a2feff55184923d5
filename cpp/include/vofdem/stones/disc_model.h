// Disc stones: the paper's circles in the x-z plane (Maeno & Tomita 2008, sec. 2.2), each standing for
// the sphere of its diameter d = 2 r:
//
//   V = pi d^3 / 6,   I = f M r^2 (f = DEMParams::inertia_factor: 0.4 a sphere, 0.5 a disc),
//   A_p = pi r^2 (the same from every direction)
//
// Contacts (dem_contact.h): one point per touching pair, on the line of centres, the normal overlap
// r_i + r_j - |x_j - x_i|, the tangential spring xi in ContactPair::xi; the rolling resistance of
// rolling_resistance.h where it is on. Stable step: the normal mode and the tangential mode with spin of
// two of the lightest stones, pi / (10 omega), and no more than the explicit dashpots allow in a packing
// (DEMSystem::kPackedContacts contacts per stone). Footprint: the exact disc-rectangle areas, or the
// paper's lookup table (porosity_map.h). Drag: eqs. (16)-(18) with the sphere's area pi d^2 / 4.
#pragma once

#include "vofdem/stones/stone_model.h"

namespace vofdem {

class DiscModel : public StoneModel {
 public:
  const char* name() const override { return "disc"; }
  double volume(const DEMSystem& s, int i) const override;
  double inertia(const DEMSystem& s, int i, double mass) const override;
  double nominal_diameter(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i, double ux, double uz) const override;
  double stable_dt(const DEMSystem& s) const override;
  ContactTally contact_forces(DEMSystem& s, double dt) override;
  ContactTally wall_forces(DEMSystem& s, double dt) override;
  bool lookup_footprint() const override { return true; }
  void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const override;
  DragForce drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho, double nu,
                 DragLaw law, double* slope) const override;
  double drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                            double rho, double nu) const override;
  double gap(const DEMSystem& s, int i, double x, double z) const override;
  bool covers(const DEMSystem& s, int i, double x, double z) const override;
  double outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const override;
  std::unique_ptr<StonePacking> packing(const WeirSpec& spec) const override;
};

}  // namespace vofdem
