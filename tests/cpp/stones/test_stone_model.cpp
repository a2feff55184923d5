// The stone-model seam (stone_model.h): the registry, a model switched by name, its part of the state,
// and a model the library does not know (frictionless_disc_model.h) registered with one line and run
// through coupled steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "stones/frictionless_disc_model.h"
#include "vofdem/stones/stone_model.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem {
namespace {

// the test model's registration: the one line a program adds for a model of its own
const bool kRegistered =
    (register_stone_model("frictionless_disc", [] { return std::make_unique<test::FrictionlessDiscModel>(); }), true);

TEST(StoneModel, RegistryListsTheBuiltInModelsFirstAndRefusesUnknownOrTakenNames) {
  ASSERT_TRUE(kRegistered);
  const std::vector<std::string> names = stone_model_names();
  ASSERT_GE(names.size(), 3u);
  EXPECT_EQ(names[0], "disc");
  EXPECT_EQ(names[1], "polygon");
  EXPECT_NE(std::find(names.begin(), names.end(), "frictionless_disc"), names.end());
  for (const std::string& n : names) EXPECT_EQ(make_stone_model(n)->name(), n);
  try {
    make_stone_model("cube");
    FAIL() << "an unknown model was made";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'cube' is not one of the registered stone models 'disc', 'polygon'"),
              std::string::npos) << e.what();
  }
  EXPECT_THROW(register_stone_model("disc", [] { return std::make_unique<test::FrictionlessDiscModel>(); }),
               std::invalid_argument);
  EXPECT_THROW(register_stone_model("", [] { return std::make_unique<test::FrictionlessDiscModel>(); }),
               std::invalid_argument);
}

TEST(StoneModel, SetModelByNameAndTheStateCarriesItsModel) {
  DEMParams p;
  p.add_flume(0.0, 1.0, 0.0);
  DEMSystem a(p, {0.2, 0.0235, 0.3, 0.0235}, {0.024, 0.024}, {2650.0});
  EXPECT_STREQ(a.model().name(), "disc");
  EXPECT_THROW(a.set_model("cube"), std::invalid_argument);
  EXPECT_STREQ(a.model().name(), "disc");  // unchanged by the refused call
  a.set_model("frictionless_disc");
  EXPECT_STREQ(a.model().name(), "frictionless_disc");
  a.advance(0.01);
  DEMState s;
  a.export_state(s);
  EXPECT_EQ(s.model, "frictionless_disc");
  // a disc system takes the state's model with the state
  DEMSystem b(p, 2);
  b.import_state(s);
  EXPECT_STREQ(b.model().name(), "frictionless_disc");
  // and the checkpoint's map names the model only by a key of its own: none here, so it reads back as
  // the default (the test model keeps no state of its own)
  EXPECT_EQ(dem_state_from_map(dem_state_to_map(s), p.walls.size()).model, "disc");
}

TEST(StoneModel, ATestModelRunsThroughCoupledStepsWithoutTurningAndRestsOnTheBed) {
  // two 4.8 cm stones dropped into a 0.2 m pool (1 cm cells), two-way coupling, the test model's stones
  const double r = 0.024;
  test::Scene s = test::tank(0.3, 0.4, 0.01, 0.2, {0.1, 0.3, 0.2, 0.25}, r, kCoupleTwoWay);
  s.stones->set_model("frictionless_disc");
  const double v0 = s.sim->water_volume();
  double worst = 0.0;
  while (s.sim->time() < 1.0) {
    s.sim->step();
    worst = std::max(worst, std::abs(s.sim->water_volume() - v0) / v0);
  }
  EXPECT_LT(worst, 1e-9);                          // the porosity map took the model's footprint
  EXPECT_GT(s.sim->redistributed_volume(), 0.0);  // the stones displaced water on the way down
  const double g = 9.81, rho_w = s.fluid->params().medium.rho_water;
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(s.stones->stone_omega[i], 0.0);  // no torque: the stones never turn
    EXPECT_EQ(s.stones->stone_angle[i], 0.0);
    // at rest on the bed, pressed in by the buoyant weight (M - rho_w V) g over k_n
    const double overlap = (s.stones->mass(i) - rho_w * s.stones->volume(i)) * g / s.stones->stiffness_normal();
    EXPECT_NEAR(s.stones->stone_pos[2 * i + 1], r - overlap, 0.05 * overlap) << "stone " << i;
    EXPECT_LT(std::abs(s.stones->stone_vel[2 * i + 1]), 1e-3) << "stone " << i;  // (free to slide: no friction)
  }
  // the flow sees the stone: the cell at its centre holds solid
  const Grid2D& grid = s.fluid->grid();
  const int c = grid.cell(grid.locate_x(s.stones->stone_pos[0]), grid.locate_z(s.stones->stone_pos[1]));
  EXPECT_LT(s.fluid->cell_porosity[c], 0.9);
}

// the packing generator asks the model how to draw and place its stones: a model without a packing is
// refused with the key named, and an unknown name with the registered ones
TEST(StoneModel, ThePackingGeneratorRefusesAModelWithoutAPackingAndNamesTheKey) {
  ASSERT_TRUE(kRegistered);
  WeirSpec spec;
  WeirPackingReport report;
  spec.d_mean = 0.048;
  spec.density = 2650.0;
  spec.shape = "frictionless_disc";
  try {
    pack_weir(spec, DEMParams{}, report);
    FAIL() << "packed a model without a packing";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "shape = 'frictionless_disc': the packing generator cannot pack this stone model");
  }
  spec.shape = "cube";
  try {
    pack_weir(spec, DEMParams{}, report);
    FAIL() << "packed an unknown model";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shape = 'cube' is not one of the registered stone models"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vofdem
