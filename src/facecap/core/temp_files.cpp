#include "facecap/core/temp_files.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstring>

namespace facecap {

namespace {

// A fixed table, so that the signal handler reads it without locks or
// allocation. Each slot's tag is (generation << 2) | state: the handler
// copies a path only between two equal readings of an "in use" tag, so a slot
// rewritten meanwhile (a new generation) is never removed under an old name.
constexpr int kSlots = 512;
constexpr size_t kMaxPath = 1024;
constexpr uint64_t kFree = 0, kWriting = 1, kInUse = 2;

struct Slot {
  std::atomic<uint64_t> tag{0};
  char path[kMaxPath];
};
Slot g_slots[kSlots];
static_assert(std::atomic<uint64_t>::is_always_lock_free, "the signal handler needs a lock-free tag");

}  // namespace

RegisteredTempFile::RegisteredTempFile(const std::filesystem::path& path) : slot_(-1) {
  const std::string& s = path.native();
  if (s.size() >= kMaxPath) return;
  for (int k = 0; k < kSlots; ++k) {
    uint64_t tag = g_slots[k].tag.load(std::memory_order_relaxed);
    if ((tag & 3) != kFree) continue;
    const uint64_t generation = (tag >> 2) + 1;
    if (!g_slots[k].tag.compare_exchange_strong(tag, generation << 2 | kWriting, std::memory_order_acquire)) continue;
    std::memcpy(g_slots[k].path, s.c_str(), s.size() + 1);
    g_slots[k].tag.store(generation << 2 | kInUse, std::memory_order_release);
    slot_ = k;
    return;
  }
}

RegisteredTempFile::~RegisteredTempFile() {
  if (slot_ < 0) return;
  const uint64_t tag = g_slots[slot_].tag.load(std::memory_order_relaxed);
  g_slots[slot_].tag.store((tag >> 2) << 2 | kFree, std::memory_order_release);
}

void remove_registered_temp_files() noexcept {
  char path[kMaxPath];
  for (Slot& slot : g_slots) {
    const uint64_t before = slot.tag.load(std::memory_order_acquire);
    if ((before & 3) != kInUse) continue;
    size_t n = 0;
    while (n + 1 < kMaxPath && slot.path[n] != '\0') {
      path[n] = slot.path[n];
      ++n;
    }
    path[n] = '\0';
    std::atomic_thread_fence(std::memory_order_acquire);
    if (slot.tag.load(std::memory_order_relaxed) == before) ::unlink(path);
  }
}

}  // namespace facecap
