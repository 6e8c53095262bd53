#pragma once
// The machine simulation's plot (simulate_program.hpp) as a standalone SVG: the contour error along the
// program (its largest value in each of a few hundred slices of time, with the worst line marked), and the
// commanded and the actual tool path seen from above (the error magnified so that it shows).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "servo/servo_plant.hpp"

namespace pkm::pipeline {

struct SimulateResult;

std::string simulate_plot_svg(const servo::ServoRunInput& input,
                              const std::vector<Eigen::Vector3d>& contour_mm, const SimulateResult& result);

}  // namespace pkm::pipeline
