#include <gtest/gtest.h>

#include <stdexcept>

#include "vofdem/grid.h"

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
