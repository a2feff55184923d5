#include "vofdem/coupling/overflow_load.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vofdem/common/check.h"
#include "vofdem/stones/wet_fraction.h"

namespace vofdem {

void OverflowLoadParams::validate() const {
  require_in_open_closed("overflow_drag_coefficient", drag_coefficient, 0.0, 5.0);
  require_in_closed("overflow_lift_coefficient", lift_coefficient, 0.0, 5.0);
  require_in_open_closed("overflow_band_height", band_height, 0.0, 5.0);
}

namespace {
// the upper outline of one stone at x: its half-ellipse, -inf outside its extent
double upper_outline(const StoneExtent& e, double x) {
  const double a = 0.5 * (e.x_hi - e.x_lo), xc = 0.5 * (e.x_hi + e.x_lo);
  const double b = 0.5 * (e.z_hi - e.z_lo), zc = 0.5 * (e.z_hi + e.z_lo);
  if (!(a > 0.0)) return -std::numeric_limits<double>::infinity();
  const double s = (x - xc) / a;
  if (s <= -1.0 || s >= 1.0) return -std::numeric_limits<double>::infinity();
  return zc + b * std::sqrt(1.0 - s * s);
}
}  // namespace

double surface_of_others(int j, double x, int count, const StoneExtent* extents, const std::uint8_t* active) {
  double s = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < count; ++k) {
    if (k == j || !active[k]) continue;
    const StoneExtent& e = extents[k];
    if (x <= e.x_lo || x >= e.x_hi) continue;
    s = std::max(s, upper_outline(e, x));
  }
  return s;
}

double stone_protrusion(int j, int count, const StoneExtent* extents, const std::uint8_t* active) {
  const StoneExtent& e = extents[j];
  const double h = e.z_hi - e.z_lo;
  // a stone above its top at its centre: buried
  if (surface_of_others(j, 0.5 * (e.x_lo + e.x_hi), count, extents, active) >= e.z_hi) return 0.0;
  // a flank no other stone covers is the bed under the stone: its bottom
  auto flank = [&](double x) { return std::max(surface_of_others(j, x, count, extents, active), e.z_lo); };
  const double ref = 0.5 * (flank(e.x_lo) + flank(e.x_hi));
  return std::clamp(e.z_hi - ref, 0.0, h);
}

double exposed_share(double protrusion, double height) {
  if (!(height > 0.0) || !(protrusion > 0.0)) return 0.0;
  // the share of the outline's projection below the level height - protrusion above its bottom
  const double s = 1.0 - 2.0 * protrusion / height;
  return 1.0 - disc_wet_fraction(s);
}

DragForce overflow_force(double a_exp, double ur, double wr, double wet, double rho, const OverflowLoadParams& p) {
  if (!(a_exp > 0.0) || !(wet > 0.0)) return {0.0, 0.0};
  const double speed = std::hypot(ur, wr);
  const double q = 0.5 * rho * a_exp * wet;
  return {q * p.drag_coefficient * speed * ur, q * (p.drag_coefficient * speed * wr + p.lift_coefficient * speed * speed)};
}

namespace {
bool open_x(const Grid2D& g, int f_i, int k, const double* n) { return f_i > 0 && f_i < g.nx() && n[g.face_x(f_i, k)] > 0.0; }
bool open_z(const Grid2D& g, int i, int f_k, const double* n) { return f_k > 0 && f_k < g.nz() && n[g.face_z(i, f_k)] > 0.0; }
}  // namespace

bool overflow_band_cell(const Grid2D& g, int i, int k, const double* face_x_n, const double* face_z_n) {
  return (open_x(g, i, k, face_x_n) || open_x(g, i + 1, k, face_x_n)) &&
         (open_z(g, i, k, face_z_n) || open_z(g, i, k + 1, face_z_n));
}

void apply_overflow_reaction(const Grid2D& g, const double* face_x_n, const double* face_z_n, const double* reaction,
                             double dt, double rho, double* face_u, double* face_w) {
  for (int k = 0; k < g.nz(); ++k) {
    const double scale = dt / (rho * g.cell_area(k));
    for (int i = 0; i < g.nx(); ++i) {
      const int c = g.cell(i, k);
      const double rx = reaction[2 * c], rz = reaction[2 * c + 1];
      if (rx == 0.0 && rz == 0.0) continue;
      const bool xl = open_x(g, i, k, face_x_n), xr = open_x(g, i + 1, k, face_x_n);
      const bool zb = open_z(g, i, k, face_z_n), zt = open_z(g, i, k + 1, face_z_n);
      const int mx = xl + xr, mz = zb + zt;
      // a band samples only cells with an open face each way (overflow_band_cell): mx, mz > 0
      if (mx > 0) {
        const double du = rx * scale / mx;
        if (xl) face_u[g.face_x(i, k)] += du;
        if (xr) face_u[g.face_x(i + 1, k)] += du;
      }
      if (mz > 0) {
        const double dw = rz * scale / mz;
        if (zb) face_w[g.face_z(i, k)] += dw;
        if (zt) face_w[g.face_z(i, k + 1)] += dw;
      }
    }
  }
}

}  // namespace vofdem
