#pragma once
// Comma-separated files as facecap writes them (no quoting).
#include <string>
#include <vector>

namespace facecap {

// The fields of `line`; a trailing comma ends with an empty field.
std::vector<std::string> split_csv_line(const std::string& line);

// A number as the tables write it: six significant digits (%.6g), as
// spreadsheets show them.
std::string csv_number(double v);

}  // namespace facecap
