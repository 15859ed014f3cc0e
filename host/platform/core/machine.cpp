// SPDX-License-Identifier: MIT
#include "platform/core/machine.hpp"

#include <algorithm>
#include <thread>

namespace smi::machine {

int cores() {
  static const int n = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<int>(n);
}

int cap_threads(long long requested) {
  if (requested < 1) return 1;
  return static_cast<int>(std::min<long long>(requested, cores()));
}

}  // namespace smi::machine
