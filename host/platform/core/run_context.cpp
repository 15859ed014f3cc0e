#include "platform/core/run_context.hpp"

#include <cstdio>

namespace smi {

WarningSink& WarningSink::operator=(const WarningSink& o) {
  if (this == &o) return *this;
  std::vector<std::string> c = o.collected();
  const std::lock_guard<std::mutex> lock(mu_);
  print_ = o.print_;
  collected_ = std::move(c);
  return *this;
}

void WarningSink::warn(std::string_view source, std::string_view text) {
  const std::lock_guard<std::mutex> lock(mu_);
  collected_.push_back(std::string(source) + ": " + std::string(text));
  if (print_) {
    std::fprintf(stderr, "%.*s: warning: %.*s\n", static_cast<int>(source.size()), source.data(),
                 static_cast<int>(text.size()), text.data());
    std::fflush(stderr);
  }
}

std::vector<std::string> WarningSink::collected() const {
  const std::lock_guard<std::mutex> lock(mu_);
  return collected_;
}

}  // namespace smi
