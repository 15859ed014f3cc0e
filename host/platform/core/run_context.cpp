// SPDX-License-Identifier: MIT
#include "platform/core/run_context.hpp"

#include <cstdio>

namespace smi {

WarningSink& WarningSink::operator=(const WarningSink& o) {
  if (this == &o) return *this;
  std::vector<std::string> c;
  std::size_t n = 0;
  {
    const std::lock_guard<std::mutex> lock(o.mu_);
    c = o.collected_;
    n = o.counted_;
  }
  const std::lock_guard<std::mutex> lock(mu_);
  print_ = o.print_;
  collected_ = std::move(c);
  counted_ = n;
  return *this;
}

void WarningSink::warn(std::string_view source, std::string_view text) {
  const std::lock_guard<std::mutex> lock(mu_);
  if (collected_.size() >= kKept) {
    if (counted_++ == 0 && print_) {
      std::fprintf(stderr, "smi-lua: warning: more than %zu warnings; the rest are counted, not shown\n", kKept);
      std::fflush(stderr);
    }
    return;
  }
  collected_.push_back(std::string(source) + ": " + std::string(text));
  if (print_) {
    std::fprintf(stderr, "%.*s: warning: %.*s\n", static_cast<int>(source.size()), source.data(),
                 static_cast<int>(text.size()), text.data());
    std::fflush(stderr);
  }
}

std::vector<std::string> WarningSink::collected() const {
  const std::lock_guard<std::mutex> lock(mu_);
  std::vector<std::string> out = collected_;
  if (counted_ > 0) out.push_back("smi-lua: " + std::to_string(counted_) + " more warning(s) counted, not kept");
  return out;
}

}  // namespace smi
