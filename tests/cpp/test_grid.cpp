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

TEST(Grid2D, RefusesBadInput) {
  EXPECT_THROW(Grid2D(0, 0.1, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Grid2D(2, -0.1, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Grid2D(2, 0.1, {0.0, 1.0, 0.5}), std::invalid_argument);
}
