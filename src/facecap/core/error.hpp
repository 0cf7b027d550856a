#pragma once
// The one exception type facecap throws for bad input and failed operations.
// Its message is a single line that names the problem (and the file, where
// there is one); the command-line program prints it and exits non-zero.
#include <stdexcept>
#include <string>

namespace facecap {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace facecap
