#pragma once
// Checks for numeric options that CLI11's own do not make: CLI::Range lets NaN through (every
// comparison with NaN is false), so "--noise nan" reached the libraries as a value.
#include <CLI/CLI.hpp>
#include <string>

namespace meadow::cli {

// A finite number within [min, max]; NaN and infinities are refused with the option's name.
CLI::Validator finiteRange(double min, double max);

}  // namespace meadow::cli
