#pragma once
// One line of a comma-separated file, as facecap writes them (no quoting).
#include <string>
#include <vector>

namespace facecap {

// The fields of `line`; a trailing comma ends with an empty field.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace facecap
