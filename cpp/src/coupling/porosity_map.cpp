#include "vofdem/coupling/porosity_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/stones/polygon.h"

namespace vofdem {

namespace {

// integral of the half chord sqrt(r^2 - t^2) from 0 to t, t in [0, r]; atan2 and (r - t)(r + t)
// stay accurate near tangency where asin(t / r) and r^2 - t^2 would lose digits
double half_chord_primitive(double t, double r) {
  const double c = std::sqrt(std::max(0.0, (r - t) * (r + t)));
  return 0.5 * (t * c + r * r * std::atan2(t, c));
}

// first grid row whose top face lies above z (the row holding z), not clamped: -1 below, nz above
int row_of(const Grid2D& g, double z) {
  const auto& zf = g.z_faces();
  return static_cast<int>(std::upper_bound(zf.begin(), zf.end(), z) - zf.begin()) - 1;
}

}  // namespace

double disc_corner_primitive(double X, double Z, double r) {
  const double sign = ((X < 0.0) != (Z < 0.0)) ? -1.0 : 1.0;
  const double x = std::min(std::fabs(X), r);
  const double z = std::min(std::fabs(Z), r);
  // below height z the disc spans |x| <= w; beyond w the column is cut by the circle, not by z
  const double w = std::sqrt(std::max(0.0, (r - z) * (r + z)));
  if (x <= w) return sign * x * z;
  return sign * (w * z + half_chord_primitive(x, r) - half_chord_primitive(w, r));
}

double disc_rect_area_unchecked(double cx, double cz, double r, double x0, double x1, double z0, double z1) {
  const double a0 = x0 - cx, a1 = x1 - cx, b0 = z0 - cz, b1 = z1 - cz;
  const double area = disc_corner_primitive(a1, b1, r) - disc_corner_primitive(a0, b1, r) -
                      disc_corner_primitive(a1, b0, r) + disc_corner_primitive(a0, b0, r);
  // round-off (of order 1e-16 r^2) may leave -1e-20 where the true area is 0, or a little more than
  // a small rectangle that lies inside the disc: keep to the bounds [0, rectangle area]
  return std::clamp(area, 0.0, (x1 - x0) * (z1 - z0));
}

double disc_rect_area(double cx, double cz, double r, double x0, double x1, double z0, double z1) {
  require_finite("cx", cx);
  require_finite("cz", cz);
  require_non_negative("r", r);
  require_finite("x0", x0);
  require_finite("z0", z0);
  require_in_closed("x1", x1, x0, INFINITY);
  require_in_closed("z1", z1, z0, INFINITY);
  return disc_rect_area_unchecked(cx, cz, r, x0, x1, z0, z1);
}

PorosityMapper::PorosityMapper(const Grid2D& grid, const PorosityParams& params) : grid_(grid), params_(params) {
  require_in_closed("n_exp", params.n_exp, 0.0, 1.0);
  require_positive("r_min", params.r_min);
  require_in_closed("r_max", params.r_max, params.r_min, INFINITY);
  require_positive("dr", params.dr);
  if (params.m < 1 || params.m > 256)
    throw std::invalid_argument("m = " + std::to_string(params.m) + " is outside the allowed range [1, 256]");
  if (params.max_discs < 0)
    throw std::invalid_argument("max_discs = " + std::to_string(params.max_discs) +
                                " is outside the allowed range [0, inf)");
  if (params.method != PorosityMethod::kExact && params.method != PorosityMethod::kLookup)
    throw std::invalid_argument("method = " + std::to_string(static_cast<int>(params.method)) +
                                " is outside the allowed range {0 (exact), 1 (lookup)}");

  const double rmax = params.r_max;
  // exact method: columns and rows a disc of radius r_max can touch (+1 for round-off in floor)
  const int max_cols = static_cast<int>(std::floor(2.0 * rmax / grid_.dx())) + 3;
  int max_rows = 1;
  for (int k = 0; k < grid_.nz(); ++k) {
    const int top = std::min(grid_.nz() - 1, row_of(grid_, grid_.z_face(k + 1) + 2.0 * rmax));
    max_rows = std::max(max_rows, top - k + 2);
  }
  max_rows = std::min(max_rows, grid_.nz());
  scratch_line_ = std::max(max_cols, max_rows) + 1;
  node_phi_.assign(static_cast<std::size_t>(max_cols + 1) * (max_rows + 1) + 3 * scratch_line_, 0.0);
  max_cells_per_disc_ = max_cols * max_rows;

  sx_ = static_cast<int>(std::floor(rmax / grid_.dx())) + 1;
  build_row_classes();
  if (params_.method == PorosityMethod::kLookup) build_tables();
  for (const RowClass& c : classes_)
    max_cells_per_disc_ = std::max(max_cells_per_disc_, (2 * sx_ + 1) * (c.dk_hi - c.dk_lo + 1));

  cell_solid_area_.assign(grid_.ncell(), 0.0);
  cell_porosity_.assign(grid_.ncell(), 1.0);
  stone_cell_offsets_.assign(static_cast<std::size_t>(params_.max_discs) + 1, 0);
  stone_cell_index_.assign(static_cast<std::size_t>(params_.max_discs) * max_cells_per_disc_, 0);
  stone_cell_area_.assign(stone_cell_index_.size(), 0.0);
  poly_scratch_.assign(16 * kPolygonMaxVertices + 64, 0.0);
  clump_patch_.assign(static_cast<std::size_t>(max_cells_per_disc_), 0.0);
  stage_map_ = profile_.add_stage("porosity_map");
}

void PorosityMapper::build_row_classes() {
  const int nz = grid_.nz();
  const double rmax = params_.r_max;
  row_class_.assign(nz, -1);
  for (int k = 0; k < nz; ++k) {
    RowClass rc;
    rc.dk_lo = std::max(0, row_of(grid_, grid_.z_face(k) - rmax)) - k;
    rc.dk_hi = std::min(nz - 1, row_of(grid_, grid_.z_face(k + 1) + rmax)) - k;
    for (int j = k + rc.dk_lo; j <= k + rc.dk_hi + 1; ++j) rc.z_rel.push_back(grid_.z_face(j) - grid_.z_face(k));
    // rows whose neighbouring faces coincide (to 1e-12 of the cell height) share a table
    const double tol = 1e-12 * grid_.dz(k);
    int found = -1;
    for (std::size_t c = 0; c < classes_.size() && found < 0; ++c) {
      const RowClass& o = classes_[c];
      if (o.dk_lo != rc.dk_lo || o.dk_hi != rc.dk_hi) continue;
      bool same = true;
      for (std::size_t q = 0; q < o.z_rel.size() && same; ++q) same = std::fabs(o.z_rel[q] - rc.z_rel[q]) <= tol;
      if (same) found = static_cast<int>(c);
    }
    if (found < 0) {
      found = static_cast<int>(classes_.size());
      classes_.push_back(std::move(rc));
    }
    row_class_[k] = found;
  }
}

void PorosityMapper::build_tables() {
  const int m = params_.m;
  const double dx = grid_.dx();
  const double span = params_.r_max - params_.r_min;
  nradius_ = span > 0.0 ? static_cast<int>(std::ceil(span / params_.dr - 1e-9)) + 1 : 1;
  nradius_ = std::max(nradius_, span > 0.0 ? 2 : 1);
  const int ncol = 2 * sx_ + 1;
  tables_.clear();
  for (const RowClass& c : classes_) {
    const int nrow = c.dk_hi - c.dk_lo + 1;
    const double* zf = c.z_rel.data();  // zf[q] is the bottom face of stencil row q
    const double dz = zf[-c.dk_lo + 1];  // the centre row spans [0, dz]
    for (int q = 0; q < nradius_; ++q) {
      const double r = nradius_ > 1 ? params_.r_min + span * q / (nradius_ - 1) : params_.r_min;
      std::vector<double> t(static_cast<std::size_t>(m) * m * ncol * nrow, 0.0);
      for (int b = 0; b < m; ++b) {
        for (int a = 0; a < m; ++a) {
          // the disc centre at the centre of sub-area (a, b) of the centre cell [0, dx] x [0, dz]
          const double xc = (a + 0.5) * dx / m, zc = (b + 0.5) * dz / m;
          double* row = &t[static_cast<std::size_t>(b * m + a) * ncol * nrow];
          for (int s = 0; s < nrow; ++s)
            for (int di = -sx_; di <= sx_; ++di)
              row[s * ncol + di + sx_] =
                  disc_rect_area_unchecked(xc, zc, r, di * dx, (di + 1) * dx, zf[s], zf[s + 1]) / (r * r);
        }
      }
      tables_.push_back(std::move(t));
    }
  }
}

std::size_t PorosityMapper::table_bytes() const {
  std::size_t bytes = 0;
  for (const auto& t : tables_) bytes += t.size() * sizeof(double);
  return bytes;
}

int PorosityMapper::add_exact(int /*j*/, double x, double z, double r, int p) {
  const CellBox box = grid_.circle_cells(x, z, r);
  if (box.empty()) return p;
  const int i0 = box.i0, k0 = box.k0, ni = box.ni, nk = box.nk;
  if (static_cast<std::size_t>(ni + 1) * (nk + 1) + 3 * scratch_line_ > node_phi_.size() || ni + 1 > scratch_line_ ||
      nk + 1 > scratch_line_ || ni * nk > max_cells_per_disc_)
    throw std::logic_error("porosity_map: disc stencil larger than its bound (r = " + format_value(r) + ")");
  // Phi at every grid node around the disc: each cell area is then four reads. The transcendental
  // parts of Phi depend on the column alone (G(|X|)) or on the row alone (w, G(w)): computed once each
  double* gx = &node_phi_[node_phi_.size() - 3 * scratch_line_];
  double* wz = gx + scratch_line_;
  double* gw = wz + scratch_line_;
  for (int i = 0; i <= ni; ++i) gx[i] = half_chord_primitive(std::min(std::fabs(grid_.x_face(i0 + i) - x), r), r);
  for (int k = 0; k <= nk; ++k) {
    const double zc = std::min(std::fabs(grid_.z_face(k0 + k) - z), r);
    wz[k] = std::sqrt(std::max(0.0, (r - zc) * (r + zc)));
    gw[k] = half_chord_primitive(wz[k], r);
  }
  for (int k = 0; k <= nk; ++k) {
    const double zr = grid_.z_face(k0 + k) - z;
    const double zc = std::min(std::fabs(zr), r);
    for (int i = 0; i <= ni; ++i) {
      const double xr = grid_.x_face(i0 + i) - x;
      const double xc = std::min(std::fabs(xr), r);
      const double phi = xc <= wz[k] ? xc * zc : wz[k] * zc + gx[i] - gw[k];
      node_phi_[k * (ni + 1) + i] = ((xr < 0.0) != (zr < 0.0)) ? -phi : phi;
    }
  }
  for (int k = 0; k < nk; ++k) {
    for (int i = 0; i < ni; ++i) {
      const double* lo = &node_phi_[k * (ni + 1) + i];
      const double* hi = lo + (ni + 1);
      const double cell_area = grid_.dx() * grid_.dz(k0 + k);
      const double area = std::clamp(hi[1] - hi[0] - lo[1] + lo[0], 0.0, cell_area);
      if (area <= 0.0) continue;
      const int c = grid_.cell(i0 + i, k0 + k);
      p = append_cell(c, area, p);
    }
  }
  return p;
}

int PorosityMapper::add_lookup(int j, double x, double z, double r, int p) {
  const double fx = (x - grid_.x0()) / grid_.dx();
  const int i = static_cast<int>(std::floor(fx));
  const int k = row_of(grid_, z);
  // the table covers centres inside the grid only
  if (i < 0 || i >= grid_.nx() || k < 0 || k >= grid_.nz()) return add_exact(j, x, z, r, p);
  const int m = params_.m;
  const int a = std::min(m - 1, static_cast<int>((fx - i) * m));
  const int b = std::min(m - 1, static_cast<int>((z - grid_.z_face(k)) / grid_.dz(k) * m));
  const RowClass& c = classes_[row_class_[k]];
  const int ncol = 2 * sx_ + 1, nrow = c.dk_hi - c.dk_lo + 1;
  const std::size_t sub = static_cast<std::size_t>(b * m + a) * ncol * nrow;
  // linear interpolation of A / r^2 between the radius nodes around r
  int q = 0;
  double w = 0.0;
  if (nradius_ > 1) {
    const double t = (r - params_.r_min) / (params_.r_max - params_.r_min) * (nradius_ - 1);
    q = std::min(static_cast<int>(t), nradius_ - 2);
    w = t - q;
  }
  const double* t0 = &tables_[row_class_[k] * nradius_ + q][sub];
  const double r2 = r * r;
  const double* t1 = nradius_ > 1 ? &tables_[row_class_[k] * nradius_ + q + 1][sub] : t0;
  // columns of the stencil inside the grid
  const int di_lo = std::max(-sx_, -i), di_hi = std::min(sx_, grid_.nx() - 1 - i);
  for (int s = 0; s < nrow; ++s) {
    const int kk = k + c.dk_lo + s;
    for (int di = di_lo; di <= di_hi; ++di) {
      const int ii = i + di;
      const int e = s * ncol + di + sx_;
      const double area = r2 * (t0[e] + w * (t1[e] - t0[e]));
      if (area <= 0.0) continue;
      const int cell = grid_.cell(ii, kk);
      p = append_cell(cell, area, p);
    }
  }
  return p;
}

void PorosityMapper::map(int n, const double* disc_x, const double* disc_z, const double* disc_r,
                         const std::uint8_t* stone_active) {
  const bool lookup = params_.method == PorosityMethod::kLookup;
  map_each(
      n, stone_active,
      [&](int j) {
        require_finite("disc_x", disc_x[j]);
        require_finite("disc_z", disc_z[j]);
        require_in_closed("disc_r", disc_r[j], params_.r_min, params_.r_max);
      },
      [&](int j, int p) {
        return lookup ? add_lookup(j, disc_x[j], disc_z[j], disc_r[j], p) : add_exact(j, disc_x[j], disc_z[j], disc_r[j], p);
      });
}

// eq. (11) with A_s capped at the cell area
void PorosityMapper::apply_eq11() {
  for (int k = 0; k < grid_.nz(); ++k) {
    const double ac = grid_.cell_area(k);
    for (int i = 0; i < grid_.nx(); ++i) {
      const int c = grid_.cell(i, k);
      cell_solid_area_[c] = std::min(cell_solid_area_[c], ac);
      cell_porosity_[c] = porosity_eq11(cell_solid_area_[c], ac, params_.n_exp);
    }
  }
}

void PorosityMapper::map(const std::vector<double>& disc_x, const std::vector<double>& disc_z,
                         const std::vector<double>& disc_r) {
  if (disc_z.size() != disc_x.size() || disc_r.size() != disc_x.size())
    throw std::invalid_argument("disc_x, disc_z and disc_r must have the same length");
  map(static_cast<int>(disc_x.size()), disc_x.data(), disc_z.data(), disc_r.data(), nullptr);
}

}  // namespace vofdem
