// Comparing two .tsp files: what a partitioned (or otherwise different) build must reproduce.
#pragma once
#include <filesystem>
#include <string>

namespace tsptest {
/// Expects (gtest) every stored brick at every step, the stencil and inside fractions, every
/// node's statistics, the level residuals, the ranges, histogram and geometry of field `field`
/// (empty: the first) of b to equal a's bit for bit, a to be a serial build and b built by
/// `ranks` processes (build_ranks).
void expect_same_build(const std::filesystem::path& a, const std::filesystem::path& b, int ranks,
                       const std::string& field = "");
}  // namespace tsptest
