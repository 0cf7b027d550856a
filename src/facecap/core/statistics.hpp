#pragma once
// Summary statistics the evaluations report.
#include <vector>

namespace facecap {

// Pearson correlation of two equally long samples; 0 when either is constant
// (or empty).
double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b);

// The middle value (the upper one of an even count); 0 for an empty sample.
double median(std::vector<double> values);

}  // namespace facecap
