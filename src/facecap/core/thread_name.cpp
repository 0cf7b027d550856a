#include "facecap/core/thread_name.hpp"

#include <pthread.h>

#include <cstring>

namespace facecap {

void name_this_thread(const char* name) {
  char kept[16] = {};
  std::strncpy(kept, name, sizeof kept - 1);
  pthread_setname_np(pthread_self(), kept);  // a failure leaves the old name: nothing to report
}

}  // namespace facecap
