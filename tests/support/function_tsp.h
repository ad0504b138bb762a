// A .tsp file built from a formula, for rendering tests that compare against analytic pictures.
#pragma once
#include <functional>
#include <string>

#include "tsp/core/types.h"

namespace tsptest {

/// Builds the series f(x, y, z, t) of `steps` steps over dims, quantized over [0, 1], with
/// bricks of `brick`, into a fresh file `name`.tsp in the test's temporary directory; returns its
/// path. Throws what tsp::build_tsp_file throws.
std::string build_function_tsp(const std::string& name, tsp::Dims dims,
                               const std::function<float(int, int, int, int)>& f,
                               int brick = 16, int steps = 1);

}  // namespace tsptest
