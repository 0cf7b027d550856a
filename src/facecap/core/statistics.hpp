#pragma once
// Summary statistics the evaluations report.
#include <vector>

namespace facecap {

// Pearson correlation of two equally long samples; 0 when either is constant
// (or empty).
double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace facecap
