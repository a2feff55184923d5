#include "vofdem/common/grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"

namespace vofdem {

Grid2D::Grid2D(int nx, double dx, std::vector<double> z_faces, double x0)
    : nx_(nx), nz_(static_cast<int>(z_faces.size()) - 1), dx_(dx), x0_(x0), z_faces_(std::move(z_faces)) {
  if (nx < 1) throw std::invalid_argument("nx = " + std::to_string(nx) + " is outside the allowed range [1, inf)");
  if (nz_ < 1) throw std::invalid_argument("z_faces must hold at least 2 heights (1 row of cells)");
  require_positive("dx", dx);
  require_finite("x0", x0);
  for (int k = 0; k < nz_; ++k) {
    require_finite("z_faces", z_faces_[k]);
    if (!(z_faces_[k + 1] > z_faces_[k]))
      throw std::invalid_argument("z_faces must be strictly increasing; z_faces[" + std::to_string(k + 1) +
                                  "] = " + format_value(z_faces_[k + 1]) + " <= z_faces[" + std::to_string(k) +
                                  "] = " + format_value(z_faces_[k]));
  }
}

Grid2D Grid2D::uniform(int nx, int nz, double length_x, double height_z, double x0, double z0) {
  require_positive("length_x", length_x);
  require_positive("height_z", height_z);
  if (nx < 1) throw std::invalid_argument("nx = " + std::to_string(nx) + " is outside the allowed range [1, inf)");
  if (nz < 1) throw std::invalid_argument("nz = " + std::to_string(nz) + " is outside the allowed range [1, inf)");
  std::vector<double> zf(nz + 1);
  for (int k = 0; k <= nz; ++k) zf[k] = z0 + height_z * k / nz;
  return Grid2D(nx, length_x / nx, std::move(zf), x0);
}

Grid2D Grid2D::graded(int nx, double length_x, double height_z, double dz, double dz_bed, double z_bed_top,
                      double merge_fraction) {
  require_positive("length_x", length_x);
  require_positive("height_z", height_z);
  require_positive("dz", dz);
  require_positive("dz_bed", dz_bed);
  require_in_closed("z_bed_top", z_bed_top, 0.0, height_z);
  if (!(merge_fraction >= 0.0 && merge_fraction < 1.0))
    throw std::invalid_argument("merge_fraction = " + format_value(merge_fraction) +
                                " is outside the allowed range [0, 1)");
  std::vector<double> zf{0.0};
  // rows of `step` up to `top`; a remainder of at most merge_fraction steps joins the row below it: a
  // sliver row would bind the advective limit of the flow through it (the open top's air). A face
  // closer than 1e-9 m to the target is the target: guards against round-off rows
  const double eps = 1e-9;
  const auto fill = [&](double top, double step) {
    const double last = (1.0 + merge_fraction) * step + eps;
    while (zf.back() < top - eps) zf.push_back(top - zf.back() <= last ? top : zf.back() + step);
  };
  fill(z_bed_top, dz_bed);
  fill(height_z, dz);
  if (nx < 1) throw std::invalid_argument("nx = " + std::to_string(nx) + " is outside the allowed range [1, inf)");
  return Grid2D(nx, length_x / nx, std::move(zf), 0.0);
}

double Grid2D::min_dz() const {
  double m = dz(0);
  for (int k = 1; k < nz_; ++k) m = std::min(m, dz(k));
  return m;
}

int Grid2D::locate_x(double x) const {
  const int i = static_cast<int>(std::floor((x - x0_) / dx_));
  return std::clamp(i, 0, nx_ - 1);
}

int Grid2D::locate_z(double z) const {
  const auto it = std::upper_bound(z_faces_.begin(), z_faces_.end(), z);
  const int k = static_cast<int>(it - z_faces_.begin()) - 1;
  return std::clamp(k, 0, nz_ - 1);
}

CellBox Grid2D::circle_cells(double x, double z, double r) const {
  if (x + r <= x0_ || x - r >= x_face(nx_) || z + r <= z_faces_.front() || z - r >= z_faces_.back()) return {};
  const int i0 = locate_x(x - r), k0 = locate_z(z - r);
  return {i0, k0, locate_x(x + r) - i0 + 1, locate_z(z + r) - k0 + 1};
}

}  // namespace vofdem
