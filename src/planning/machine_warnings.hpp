#pragma once
// What a plan cannot check because the machine file does not say it. Without actuator limits every pose the
// inverse kinematics solves counts as reachable; without a program origin, program X0 Y0 Z0 is the origin of
// the base frame, which on most machines is far from anything the tool can reach (a hexapod's base plane).
// The plan still holds what it claims (the path error check refuses a plan that leaves the path); these
// warnings say what it does not claim. They go to the summary and, from the command line, to stderr.
#include <string>
#include <vector>

#include "machine/machine.hpp"

namespace pkm::planning {

/// One sentence per thing the machine file leaves unchecked, naming the key to add; empty when it gives all.
std::vector<std::string> machine_warnings(const Machine& machine);

}  // namespace pkm::planning
