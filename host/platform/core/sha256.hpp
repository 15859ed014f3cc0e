// SPDX-License-Identifier: MIT
#pragma once
// SHA-256 (FIPS 180-4) by nettle (Debian's nettle-dev): a maintained implementation behind the
// small interface the tree uses (incremental update, length-framed fields, hex). The evaluation store
// keys solver runs by content (rendered deck, program, version), and provenance hashes scripts
// and libraries: a collision-resistant hash is what lets a store be shared between studies and
// teammates without false hits, and what lets `smi-lua verify` catch a changed file.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <nettle/sha2.h>

namespace smi {

class Sha256 {
 public:
  Sha256();
  /// Feeds bytes; may be called any number of times before digest().
  Sha256& update(std::string_view bytes);
  /// Feeds a field followed by its length, so that ("ab","c") and ("a","bc") hash differently.
  Sha256& field(std::string_view bytes);
  /// The 32-byte digest; the object must not be updated afterwards.
  std::array<std::uint8_t, 32> digest();
  /// The digest as 64 lowercase hex characters.
  std::string hex();

 private:
  sha256_ctx ctx_;
  std::array<std::uint8_t, 32> digest_{};
  bool done_ = false;
};

/// Hex SHA-256 of a byte string.
std::string sha256_hex(std::string_view bytes);

/// Hex SHA-256 of a file's contents; throws smi::Error naming the file if it cannot be read.
std::string sha256_file(const std::string& path);

/// Hex SHA-256 of the open file `fd` (read with pread from offset 0) up to its end or `limit`
/// bytes, whichever comes first (a file that grows while it is read cannot keep the reader
/// going); `name` names it in errors.
std::string sha256_fd(int fd, const std::string& name, std::uint64_t limit = UINT64_MAX);

}  // namespace smi
