// SPDX-License-Identifier: MIT
#pragma once
// A model computed in Lua, called from the kernels' threads. One Lua state runs one call at a
// time, but a calibration's evaluation is mostly C++ (the KDE sums, the metric): with a gate,
// bootstrap replicates and multistart starts run side by side and take turns only inside the
// model. Each turn runs in a protected call of its own on the calling thread, so a Lua error
// (a memory limit reached while pushing the design, an error in the model) is caught on the
// thread that raised it and comes back to the kernel as a C++ exception of the same type as on
// one thread: never a Lua error crossing a thread pool. The model must be a function of its
// argument (the same X gives the same outputs whatever the order of calls).
#include <lua.hpp>

#include <functional>
#include <memory>
#include <mutex>

namespace smi::bind::improve {

class LuaGate {
 public:
  explicit LuaGate(lua_State* L) : L_(L), mutex_(std::make_shared<std::mutex>()) {}
  /// Runs body (which uses the Lua state) alone, inside its own pcall; rethrows on this thread
  /// what body threw (a std::exception keeps its type) or the Lua error it raised (a LuaError).
  void run(const std::function<void()>& body) const;

 private:
  lua_State* L_;
  std::shared_ptr<std::mutex> mutex_;  ///< shared by the copies the kernels make of a model
};

}  // namespace smi::bind::improve
