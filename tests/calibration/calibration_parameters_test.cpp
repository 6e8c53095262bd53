// The parameter vector of a mechanism's geometry groups (calibration_parameters.hpp).
#include "calibration/calibration_parameters.hpp"

#include <gtest/gtest.h>

#include "calib_test_support.hpp"

namespace pkm::calibration {
namespace {

TEST(CalibParameters, HexapodWithOffsetsHas42NamedParameters) {
  auto model = calib_ch5_model();
  auto layout = parameter_layout(*model);
  ASSERT_TRUE(layout) << layout.error().message;
  ASSERT_EQ(layout->size(), 42);
  EXPECT_EQ(layout->names[0], "A1.x");
  EXPECT_EQ(layout->names[8], "A3.z");
  EXPECT_EQ(layout->names[18 + 14], "B5.z");
  EXPECT_EQ(layout->names[38], "dL3");
  EXPECT_EQ(parameter_index(*layout, "dL3"), 38);
  EXPECT_EQ(parameter_index(*layout, "C1.x"), -1);
  EXPECT_EQ(layout->actuator_count, 6);
  for (int i = 0; i < 42; ++i) EXPECT_EQ(layout->scale[i], 1.0);  // all in mm
  const Eigen::VectorXd values = parameter_vector(layout->groups);
  EXPECT_DOUBLE_EQ(values[3], 200.0);        // A2.x
  EXPECT_DOUBLE_EQ(values[18 + 2], -150.0);  // B1.z: the tool 150 mm above the joint plane
  EXPECT_DOUBLE_EQ(values[41], 0.0);         // dL6
}

TEST(CalibParameters, RebuiltMechanismUsesTheNewValues) {
  auto model = calib_ch5_model();
  auto layout = parameter_layout(*model);
  ASSERT_TRUE(layout);
  Eigen::VectorXd values = parameter_vector(layout->groups);
  values[parameter_index(*layout, "dL2")] = 0.25;
  values[parameter_index(*layout, "A1.x")] += 1.0;
  auto rebuilt = mechanism_with_parameters(*model, *layout, values);
  ASSERT_TRUE(rebuilt) << rebuilt.error().message;
  EXPECT_EQ(parameter_vector((*rebuilt)->geometry_parameters()), values);
  auto before = model->inverse(model->home());
  auto after = (*rebuilt)->inverse(model->home());
  ASSERT_TRUE(before && after);
  EXPECT_NEAR((*after)[1] - (*before)[1], -0.25, 1e-12);  // reading = geometric length − dL
  EXPECT_GT(std::abs((*after)[0] - (*before)[0]), 0.1);   // A1 moved by 1 mm
  EXPECT_FALSE(mechanism_with_parameters(*model, *layout, values.head(41)));
}

}  // namespace
}  // namespace pkm::calibration
