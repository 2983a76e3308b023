#pragma once
// The terminal's table of fitted model parameters (the body's offsets and
// any refitted rods' stiffness or effect values), shared by compare and
// diagnose.
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"

namespace rigflex::app {

// "body[ and rods' stiffness][ and effects' values]": what the table holds.
std::string fitted_parameters_label(const std::vector<diagnose::FittedParameter>& ps);
// One line per parameter: offset, std, unit, stated std, OFF beyond it.
void print_parameter_table(const std::vector<diagnose::FittedParameter>& ps);

}  // namespace rigflex::app
