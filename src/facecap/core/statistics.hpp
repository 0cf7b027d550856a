#pragma once
// Summary statistics the evaluations report.
#include <vector>

namespace facecap {

// Pearson correlation of two equally long samples; 0 when either is constant
// (or empty).
double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b);

// Standard deviation of a sample about its mean (dividing by its size, not
// size - 1); 0 for an empty sample.
double standard_deviation(const std::vector<double>& values);

// The middle value (the upper one of an even count); 0 for an empty sample.
double median(std::vector<double> values);

// The same for a sample the caller may have reordered: no copy is made.
// `values` must not be empty.
float median_in_place(std::vector<float>& values);

// The value a share (0 to 1) of the way up the sorted sample, without
// interpolation; reorders `values`, which must not be empty.
float quantile(std::vector<float>& values, float share);

}  // namespace facecap
