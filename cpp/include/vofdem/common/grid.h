// Geometry of the vertical 2D staggered (MAC) grid shared by the flow, the VOF advection, the pressure
// solver and the porosity mapping.
//
// x runs along the flume (uniform spacing dx), z upwards (spacing free per row, e.g. 0.5 cm at the
// bed and 1.0 cm above as in Maeno & Tomita 2008). Index conventions, used by every flat array:
//   cell (i, k)           c = i + nx * k          i in [0, nx), k in [0, nz)     ncell = nx * nz
//   x-face left of (i, k)  f = i + (nx + 1) * k    i in [0, nx], k in [0, nz)     nface_x = (nx + 1) * nz
//   z-face below (i, k)    f = i + nx * k          i in [0, nx), k in [0, nz]     nface_z = nx * (nz + 1)
// The grid is a pure description: it holds no field and never changes after construction.
#pragma once

#include <algorithm>
#include <vector>

namespace vofdem {

// Grid2D::graded's default: a last row of at most half its row size joins the row below (one definition:
// the binding and the scene's grid.merge_fraction take it from here)
inline constexpr double kGradedMergeFraction = 0.5;

// the two cells beside a face (Grid2D::face_x_cells, face_z_cells)
struct FaceCells {
  int a, b;  // left and right of an x-face, below and above a z-face
};

// the cells a circle reaches (Grid2D::circle_cells): columns i0 .. i0 + ni - 1, rows k0 .. k0 + nk - 1
struct CellBox {
  int i0 = 0, k0 = 0, ni = 0, nk = 0;  // ni = nk = 0: none (the circle lies wholly outside the grid)
  bool empty() const { return ni == 0; }
};

class Grid2D {
 public:
  // uniform in x: nx cells of width dx [m] from x0 [m]; z_faces [m]: nz + 1 strictly increasing heights
  Grid2D(int nx, double dx, std::vector<double> z_faces, double x0 = 0.0);

  // nx x nz uniform cells covering [x0, x0 + length_x] x [z0, z0 + height_z]
  static Grid2D uniform(int nx, int nz, double length_x, double height_z, double x0 = 0.0, double z0 = 0.0);
  // cells of dz_bed [m] up to z_bed_top [m], then dz [m] up to height_z [m]; the last row of each may
  // differ: a remainder of at most merge_fraction [-] of its row size, in [0, 1), joins the row below
  // (0.5: rows in (0.5, 1.5] of their size; 0: every remainder is a row of its own)
  static Grid2D graded(int nx, double length_x, double height_z, double dz, double dz_bed, double z_bed_top,
                       double merge_fraction = kGradedMergeFraction);

  int nx() const { return nx_; }
  int nz() const { return nz_; }
  int ncell() const { return nx_ * nz_; }
  int nface_x() const { return (nx_ + 1) * nz_; }
  int nface_z() const { return nx_ * (nz_ + 1); }

  int cell(int i, int k) const { return i + nx_ * k; }
  int face_x(int i, int k) const { return i + (nx_ + 1) * k; }
  int face_z(int i, int k) const { return i + nx_ * k; }

  // the cells beside x-face (i, k), left and right, and beside z-face (i, k), below and above; a
  // boundary face has its one cell on both sides
  FaceCells face_x_cells(int i, int k) const { return {std::max(i - 1, 0) + nx_ * k, std::min(i, nx_ - 1) + nx_ * k}; }
  FaceCells face_z_cells(int i, int k) const { return {i + nx_ * std::max(k - 1, 0), i + nx_ * std::min(k, nz_ - 1)}; }
  // the z-faces below and above cell c, and the cells below and above it (which must exist)
  int face_z_below(int c) const { return c; }
  int face_z_above(int c) const { return c + nx_; }
  int cell_below(int c) const { return c - nx_; }
  int cell_above(int c) const { return c + nx_; }

  double dx() const { return dx_; }
  double dz(int k) const { return z_faces_[k + 1] - z_faces_[k]; }
  double x0() const { return x0_; }
  double x_face(int i) const { return x0_ + dx_ * i; }
  double x_center(int i) const { return x0_ + dx_ * (i + 0.5); }
  double z_face(int k) const { return z_faces_[k]; }
  double z_center(int k) const { return 0.5 * (z_faces_[k] + z_faces_[k + 1]); }
  double length_x() const { return dx_ * nx_; }
  double height_z() const { return z_faces_.back() - z_faces_.front(); }
  double cell_area(int k) const { return dx_ * dz(k); }
  double min_dz() const;
  const std::vector<double>& z_faces() const { return z_faces_; }

  // cell index range [i, k] holding a point, clamped to the grid
  int locate_x(double x) const;
  int locate_z(double z) const;
  // the box of cells the circle of centre (x, z) [m] and radius r [m] reaches, clamped to the grid; empty
  // when the circle lies wholly outside it (touching the grid's edge does not reach it)
  CellBox circle_cells(double x, double z, double r) const;

 private:
  int nx_, nz_;
  double dx_, x0_;
  std::vector<double> z_faces_;
};

// a row of rates (non-negative; a NaN is never taken, as a comparison with it is false): when its largest
// beats `worst`, that value into `worst` and its first index into `first`. Two running maxima without a
// branch (vectorised), then a search for the first index at them
inline bool take_row_maximum(const double* row, int count, double& worst, int& first) {
  double m0 = 0.0, m1 = 0.0;
  int i = 0;
  for (; i + 1 < count; i += 2) m0 = row[i] > m0 ? row[i] : m0, m1 = row[i + 1] > m1 ? row[i + 1] : m1;
  if (i < count) m0 = row[i] > m0 ? row[i] : m0;
  const double m = m1 > m0 ? m1 : m0;
  if (!(m > worst)) return false;
  worst = m;
  first = static_cast<int>(std::find(row, row + count, m) - row);
  return true;
}

}  // namespace vofdem
