// A number as printf writes it: the one snprintf buffer the reports, plots, option texts and
// messages share.
#pragma once
#include <string>

namespace tsp {

/// v as printf writes it under `format`, one double conversion ("%g", "%.17g", "%.2f", ...);
/// at most 63 characters.
std::string number_text(double v, const char* format = "%g");

}  // namespace tsp
