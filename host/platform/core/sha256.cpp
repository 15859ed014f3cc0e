// SPDX-License-Identifier: MIT
#include "platform/core/sha256.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <unistd.h>

#include "platform/core/errors.hpp"

namespace smi {

Sha256::Sha256() { sha256_init(&ctx_); }

Sha256& Sha256::update(std::string_view bytes) {
  sha256_update(&ctx_, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  return *this;
}

Sha256& Sha256::field(std::string_view bytes) {
  update(bytes);
  const std::string len = fmt::format("\x1f{}\x1e", bytes.size());
  return update(len);
}

std::array<std::uint8_t, 32> Sha256::digest() {
  // nettle's digest resets the context: keep the first result so digest() and hex() agree.
  if (!done_) {
    sha256_digest(&ctx_, SHA256_DIGEST_SIZE, digest_.data());
    done_ = true;
  }
  return digest_;
}

std::string Sha256::hex() {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (std::uint8_t b : digest()) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

std::string sha256_hex(std::string_view bytes) { return Sha256().update(bytes).hex(); }

std::string sha256_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read '{}': {}", path, std::strerror(errno)));
  Sha256 h;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    h.update(std::string_view(buf, static_cast<std::size_t>(in.gcount())));
  }
  if (in.bad()) throw Error(fmt::format("error reading '{}'", path));
  return h.hex();
}

}  // namespace smi

namespace smi {

std::string sha256_fd(int fd, const std::string& name, std::uint64_t limit) {
  Sha256 h;
  char buf[1 << 16];
  off_t off = 0;
  while (static_cast<std::uint64_t>(off) < limit) {
    const std::uint64_t want = std::min<std::uint64_t>(sizeof buf, limit - static_cast<std::uint64_t>(off));
    const ssize_t n = ::pread(fd, buf, static_cast<std::size_t>(want), off);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(fmt::format("cannot read '{}': {}", name, std::strerror(errno)));
    }
    if (n == 0) break;
    h.update(std::string_view(buf, static_cast<std::size_t>(n)));
    off += n;
  }
  return h.hex();
}

}  // namespace smi
