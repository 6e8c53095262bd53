// The Somov–Malyshev examples of Smirnov 2019, §1.2 (its table) and the structures pkm assigns.
#include "machine/mobility.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace pkm {
namespace {

TEST(Mobility, SeedTable) {
  EXPECT_EQ(spatial_mobility(14, {6, 6, 6, 0, 0}), 6);  // hexapod 6-UHS, Fig. 13
  EXPECT_EQ(spatial_mobility(8, {3, 6, 0, 0, 0}), 3);   // tripod Fig. 14a: 5·3, 4·6
  EXPECT_EQ(spatial_mobility(8, {6, 0, 3, 0, 0}), 3);   // tripod Fig. 14b: 5·6, 3·3
  EXPECT_EQ(spatial_mobility(14, {6, 6, 6, 0, 0}), 6);  // rotopod Fig. 15
  EXPECT_EQ(spatial_mobility(9, {4, 4, 3, 0, 0}), 3);   // tricept Fig. 16
  EXPECT_EQ(planar_mobility(8, 9, 0), 3);               // planar 3-DOF Fig. 17
  EXPECT_EQ(planar_mobility(5, 5, 0), 2);               // planar 2-DOF Fig. 22
  EXPECT_EQ(spatial_mobility(8, {6, 0, 3, 0, 0}), 3);   // spatial tripod Fig. 38, 3 R + 3 P + 3 S
  // One moving link on a single pair keeps that pair's freedoms (4- and 5-DOF pairs count too).
  EXPECT_EQ(spatial_mobility(2, {0, 0, 0, 0, 1}), 5);
  EXPECT_EQ(spatial_mobility(2, {0, 0, 0, 1, 0}), 4);
}

TEST(Mobility, EveryShippedMachineHasAsManyFreedomsAsItControls) {
  for (const char* file : {"hexapod_ch5.yaml", "hexapod_ch3.yaml", "hexapod_genhexkins.yaml",
                           "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml", "tripod.yaml",
                           "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const MechanismStructure s = structure_of(*m.mechanism);
    EXPECT_EQ(mobility(s) - s.idle_freedoms, m.mechanism->controlled_axes().count())
        << file << " " << s.notation;
  }
}

}  // namespace
}  // namespace pkm
