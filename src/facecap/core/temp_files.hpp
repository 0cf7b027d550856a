#pragma once
// Temporary files that a process quitting at once (a second Ctrl-C, which
// skips the destructors that otherwise remove them) must not leave behind:
// the signal handler removes every registered one before it exits. An
// AtomicFile registers its temporary name until it is committed or gone.
#include <filesystem>

namespace facecap {

class RegisteredTempFile {
 public:
  explicit RegisteredTempFile(const std::filesystem::path& path);
  ~RegisteredTempFile();  // unregisters (does not remove the file)
  RegisteredTempFile(const RegisteredTempFile&) = delete;
  RegisteredTempFile& operator=(const RegisteredTempFile&) = delete;

 private:
  int slot_;  // -1 where the table was full or the path too long
};

// Removes every registered file. Async-signal-safe (unlink only).
void remove_registered_temp_files() noexcept;

}  // namespace facecap
