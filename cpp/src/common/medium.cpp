// Checks of the medium shared by the flow and the stones (medium.h).
#include "vofdem/common/medium.h"

#include "vofdem/common/check.h"

namespace vofdem {

void Medium::validate() const {
  require_positive("rho_water", rho_water);
  require_positive("rho_air", rho_air);
  require_non_negative("nu_water", nu_water);
  require_non_negative("nu_air", nu_air);
  require_finite("gravity[0]", gravity[0]);
  require_finite("gravity[1]", gravity[1]);
}

}  // namespace vofdem
