#pragma once
// What the facecap program's end-to-end tests share: running the built
// program quietly and reading what it prints.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "app/command.hpp"

namespace facecap {

namespace fs = std::filesystem;

using RunResult = test::CommandResult;

// `facecap -q ARGS`, its stderr with its stdout.
inline RunResult run(const std::string& args) {
  return test::run_command(std::string(FACECAP_BINARY) + " -q " + args + " 2>&1");
}

inline int lines(const std::string& s) { return test::count_lines(s); }

// The JSON object a command prints; where it fails, an exception carrying its
// exit code and output, which fails the test there.
inline nlohmann::json json_from(const std::string& args) {
  const RunResult r = run(args);
  if (r.code != 0) throw std::runtime_error(args + " exited with " + std::to_string(r.code) + ": " + r.out);
  return nlohmann::json::parse(r.out);
}

}  // namespace facecap
