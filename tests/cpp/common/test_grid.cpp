#include <gtest/gtest.h>

#include <stdexcept>

#include "vofdem/common/grid.h"

using vofdem::CellBox;
using vofdem::Grid2D;

TEST(Grid2D, GradedMatchesThePapersMesh) {
  // 2.5 cm x 1.0 cm cells, 0.5 cm rows up to 2 cm above the bed
  const Grid2D g = Grid2D::graded(40, 1.0, 0.30, 0.01, 0.005, 0.02);
  EXPECT_EQ(g.nx(), 40);
  EXPECT_DOUBLE_EQ(g.dx(), 0.025);
  EXPECT_EQ(g.nz(), 4 + 28);
  EXPECT_NEAR(g.dz(0), 0.005, 1e-15);
  EXPECT_NEAR(g.dz(4), 0.01, 1e-15);
  EXPECT_NEAR(g.height_z(), 0.30, 1e-15);
}

TEST(Grid2D, GradedRemainderOfHalfARowJoinsTheRowBelow) {
  // the scenario's 0.45 m: 0.5 cm bed row, 1 cm rows; the last 0.5 cm joins the row below (1.5 cm)
  const Grid2D g = Grid2D::graded(4, 1.0, 0.45, 0.01, 0.005, 0.005);
  EXPECT_EQ(g.nz(), 1 + 44);
  EXPECT_NEAR(g.dz(0), 0.005, 1e-15);
  EXPECT_NEAR(g.dz(43), 0.01, 1e-15);
  EXPECT_NEAR(g.dz(44), 0.015, 1e-12);
  EXPECT_NEAR(g.height_z(), 0.45, 1e-15);
  // a remainder of more than half a row keeps its own row: 0.461 m ends in a 0.6 cm row, 0.456 m in 1.1 cm
  const Grid2D h = Grid2D::graded(4, 1.0, 0.461, 0.01, 0.005, 0.005);
  EXPECT_EQ(h.nz(), 1 + 45 + 1);
  EXPECT_NEAR(h.dz(46), 0.006, 1e-12);
  EXPECT_NEAR(Grid2D::graded(4, 1.0, 0.456, 0.01, 0.005, 0.005).dz(45), 0.011, 1e-12);
  // the same rule in the bed layer: 1.2 cm of 0.5 cm rows is 0.5 + 0.7; 1.3 cm is 0.5 + 0.5 + 0.3
  const Grid2D b = Grid2D::graded(4, 1.0, 0.1, 0.01, 0.005, 0.012);
  EXPECT_NEAR(b.dz(1), 0.007, 1e-12);
  EXPECT_NEAR(b.z_faces()[2], 0.012, 1e-15);
  const Grid2D c = Grid2D::graded(4, 1.0, 0.1, 0.01, 0.005, 0.013);
  EXPECT_NEAR(c.dz(2), 0.003, 1e-12);
  // a height below one row is one row
  EXPECT_EQ(Grid2D::graded(4, 1.0, 0.004, 0.01, 0.005, 0.0).nz(), 1);
  // merge_fraction 0: every remainder is a row (0.45 m ends in a 0.5 cm row); 0.8: 0.4525 m ends in
  // 1.75 cm (0.5: in 1 cm and 0.75 cm); outside [0, 1) refused
  const Grid2D k = Grid2D::graded(4, 1.0, 0.45, 0.01, 0.005, 0.005, 0.0);
  EXPECT_EQ(k.nz(), 1 + 44 + 1);
  EXPECT_NEAR(k.dz(45), 0.005, 1e-12);
  EXPECT_NEAR(Grid2D::graded(4, 1.0, 0.4525, 0.01, 0.005, 0.005, 0.8).dz(44), 0.0175, 1e-12);
  EXPECT_NEAR(Grid2D::graded(4, 1.0, 0.4525, 0.01, 0.005, 0.005).dz(45), 0.0075, 1e-12);
  EXPECT_THROW(Grid2D::graded(4, 1.0, 0.45, 0.01, 0.005, 0.005, 1.0), std::invalid_argument);
  EXPECT_THROW(Grid2D::graded(4, 1.0, 0.45, 0.01, 0.005, 0.005, -0.1), std::invalid_argument);
}

TEST(Grid2D, IndexingAndLocation) {
  const Grid2D g = Grid2D::uniform(4, 3, 2.0, 0.6);
  EXPECT_EQ(g.cell(3, 2), 11);
  EXPECT_EQ(g.face_x(4, 2), 14);
  EXPECT_EQ(g.face_z(3, 3), 15);
  EXPECT_EQ(g.nface_x(), 15);
  EXPECT_EQ(g.nface_z(), 16);
  EXPECT_EQ(g.locate_x(1.2), 2);
  EXPECT_EQ(g.locate_z(0.45), 2);
  EXPECT_EQ(g.locate_z(-1.0), 0);
}

TEST(Grid2D, CircleCells) {
  const Grid2D g = Grid2D::uniform(4, 3, 2.0, 0.6);  // dx = 0.5, dz = 0.2
  // a circle inside: columns 1..2, rows 0..2
  const CellBox in = g.circle_cells(1.0, 0.3, 0.25);
  EXPECT_EQ(in.i0, 1);
  EXPECT_EQ(in.ni, 2);
  EXPECT_EQ(in.k0, 0);
  EXPECT_EQ(in.nk, 3);
  // one across the left end: clamped to the first column
  const CellBox left = g.circle_cells(-0.1, 0.3, 0.2);
  EXPECT_EQ(left.i0, 0);
  EXPECT_EQ(left.ni, 1);
  // one that only touches the grid's edge, or lies beyond it, reaches no cell
  EXPECT_TRUE(g.circle_cells(-0.2, 0.3, 0.2).empty());
  EXPECT_TRUE(g.circle_cells(1.0, 0.9, 0.2).empty());
  EXPECT_FALSE(in.empty());
}

TEST(Grid2D, FaceNeighbours) {
  const Grid2D g = Grid2D::uniform(4, 3, 2.0, 0.6);
  // an inner x-face between cells (0, 1) and (1, 1); the end faces have their one cell on both sides
  EXPECT_EQ(g.face_x_cells(1, 1).a, g.cell(0, 1));
  EXPECT_EQ(g.face_x_cells(1, 1).b, g.cell(1, 1));
  EXPECT_EQ(g.face_x_cells(0, 2).a, g.cell(0, 2));
  EXPECT_EQ(g.face_x_cells(0, 2).b, g.cell(0, 2));
  EXPECT_EQ(g.face_x_cells(4, 0).a, g.cell(3, 0));
  EXPECT_EQ(g.face_x_cells(4, 0).b, g.cell(3, 0));
  // z-faces: below and above, the bed and the top with their one cell
  EXPECT_EQ(g.face_z_cells(2, 1).a, g.cell(2, 0));
  EXPECT_EQ(g.face_z_cells(2, 1).b, g.cell(2, 1));
  EXPECT_EQ(g.face_z_cells(2, 0).a, g.cell(2, 0));
  EXPECT_EQ(g.face_z_cells(2, 3).b, g.cell(2, 2));
  // the z-faces and the cells below and above cell (2, 1)
  const int c = g.cell(2, 1);
  EXPECT_EQ(g.face_z_below(c), g.face_z(2, 1));
  EXPECT_EQ(g.face_z_above(c), g.face_z(2, 2));
  EXPECT_EQ(g.cell_below(c), g.cell(2, 0));
  EXPECT_EQ(g.cell_above(c), g.cell(2, 2));
}

TEST(Grid2D, RefusesBadInput) {
  EXPECT_THROW(Grid2D(0, 0.1, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Grid2D(2, -0.1, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Grid2D(2, 0.1, {0.0, 1.0, 0.5}), std::invalid_argument);
}
