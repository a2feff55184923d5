// Settling of the stones in still water before the first coupled step (Coupler::settle; coupler.h):
//
//   (M + M') dv/dt = F_contact - (rho_s - w rho_w) V g                                     (eq. 9, still water)
//
// w the stone's wet fraction in the water as it stands (the force stage's sampling, wet_fraction.h), the
// flow frozen. The packed weir thus carries its submerged weight before any flow, and the contacts'
// springs build up under it. Reference: S. Maeno and A. Tomita (2008), ICHE 2008, eq. (9).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "coupling/coupler_stage.h"
#include "vofdem/coupling/coupler.h"

namespace vofdem {

void SettleParams::validate() const {
  require_in_open_closed("max_time", max_time, 0.0, 600.0);
  require_in_open_closed("rest_speed", rest_speed, 0.0, 1.0);
  require_in_closed("hold", hold, 0.0, 10.0);
  require_in_open_closed("chunk", chunk, 0.0, 1.0);
}

SettleReport Coupler::settle(const SettleParams& p) {
  p.validate();
  SettleReport r;
  if (!has_stones() || !(params_.flags & kCoupleDEM)) return r;
  if (st_settle_ < 0) st_settle_ = add_stage("settle");
  CoupledStage timer(profile_, cpu_profile_, st_settle_);
  share_medium();
  // each stone's wet fraction in the still water, and the level that keeps it as the stone moves; no
  // drag and no pressure gradient: the water is at rest and its weight is the buoyancy
  if (fluid_ && mapper_ && (params_.flags & kCoupleWetFraction)) {
    csr_current_ = false;
    kernel_solid_current_ = false;
    stage_fluid_forces(params_.flags & kCoupleWetFraction);
    csr_current_ = false;
    kernel_solid_current_ = false;
  }
  // the packing's criterion: every free stone slower than rest_speed for `hold` seconds
  double quiet = 0.0;
  while (r.time < p.max_time - 1e-12) {
    const double dt = std::min(p.chunk, p.max_time - r.time);
    try {
      stones_->advance(dt);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string("settle: ") + e.what());
    }
    r.time += dt;
    quiet = stones_->max_speed() < p.rest_speed ? quiet + dt : 0.0;
    if (quiet >= p.hold - 1e-12) {
      r.rested = true;
      break;
    }
  }
  r.max_speed = stones_->max_speed();
  return r;
}

}  // namespace vofdem
