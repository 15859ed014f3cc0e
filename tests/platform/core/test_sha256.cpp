// SPDX-License-Identifier: MIT
// SHA-256 against the FIPS 180-2 appendix examples (the published test vectors).
#include <catch2/catch.hpp>
#include <string>

#include "platform/core/sha256.hpp"

using smi::Sha256;
using smi::sha256_hex;

TEST_CASE("sha256 matches the FIPS 180-2 test vectors") {
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256_hex(std::string(1000000, 'a')) == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("sha256 gives the same digest fed in pieces of any size") {
  const std::string msg(1000, 'q');
  const std::string whole = sha256_hex(msg);
  for (std::size_t piece : {1u, 7u, 63u, 64u, 65u, 500u}) {
    Sha256 h;
    for (std::size_t at = 0; at < msg.size(); at += piece) h.update(std::string_view(msg).substr(at, piece));
    CHECK(h.hex() == whole);
  }
}

TEST_CASE("sha256 fields keep their boundaries") {
  CHECK(Sha256().field("ab").field("c").hex() != Sha256().field("a").field("bc").hex());
  CHECK(Sha256().field("ab").field("c").hex() == Sha256().field("ab").field("c").hex());
}
