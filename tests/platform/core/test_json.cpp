// SPDX-License-Identifier: MIT
// The one JSON codec (core/json.hpp): RFC 8259 examples, exact number round trips, the
// non-finite rule and errors that name line and column.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "platform/core/errors.hpp"
#include "platform/core/json.hpp"

namespace json = smi::json;

TEST_CASE("json reads the RFC 8259 section 13 example") {
  const json::Value v = json::read(R"({"Image": {"Width": 800, "Height": 600, "Title": "View from 15th Floor",
      "Thumbnail": {"Url": "http://www.example.com/image/481989943", "Height": 125, "Width": 100},
      "Animated": false, "IDs": [116, 943, 234, 38793]}})");
  const json::Value* img = v.find("Image");
  REQUIRE(img);
  CHECK(img->find("Width")->number() == 800);
  CHECK(img->find("Title")->string() == "View from 15th Floor");
  CHECK(img->find("Thumbnail")->find("Url")->string() == "http://www.example.com/image/481989943");
  CHECK(std::get<bool>(img->find("Animated")->v) == false);
  REQUIRE(img->find("IDs")->array().size() == 4);
  CHECK(std::get<std::int64_t>(img->find("IDs")->array()[3].v) == 38793);
}

TEST_CASE("json doubles and 64-bit integers read back bit for bit") {
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(-1, 1), e(-300, 300);
  json::Array a;
  for (int i = 0; i < 2000; ++i) a.emplace_back(u(gen) * std::pow(10.0, e(gen)));
  a.emplace_back(std::numeric_limits<double>::denorm_min());
  a.emplace_back(std::numeric_limits<double>::max());
  a.emplace_back(std::int64_t{9007199254740993});
  const json::Value back = json::read(json::write(a));
  REQUIRE(back.array().size() == a.size());
  for (std::size_t i = 0; i + 1 < a.size(); ++i) CHECK(back.array()[i].number() == a[i].number());
  CHECK(std::get<std::int64_t>(back.array().back().v) == 9007199254740993);
}

TEST_CASE("json non-finite numbers: refused with their path, or encoded and read back") {
  const double inf = std::numeric_limits<double>::infinity();
  json::Value v = json::Object{{"fit", json::Array{1.0, std::nan(""), inf, -inf}}};
  CHECK_THROWS_WITH(json::write(v), Catch::Contains("value at $.fit[2] is nan"));
  json::WriteOptions enc;
  enc.non_finite = json::NonFinite::Encode;
  const std::string text = json::write(v, enc);
  CHECK(text == R"({"fit":[1,null,1e999,-1e999]})");
  const json::Value doc = json::read(text);  // kept: find() points into it
  const json::Array& back = doc.find("fit")->array();
  CHECK(back[1].is_null());
  CHECK(back[2].number() == inf);
  CHECK(back[3].number() == -inf);
}

TEST_CASE("json writes sorted keys and indents; strings keep their bytes") {
  json::Value v = json::Object{{"b", json::Array{1, 2}}, {"a", json::Object{{"s", "q\"\\\n\x01é"}}}};
  CHECK(json::write(v) == R"({"a":{"s":"q\"\\\n\u0001é"},"b":[1,2]})");
  CHECK(json::write(v, {2}) == "{\n  \"a\": {\n    \"s\": \"q\\\"\\\\\\n\\u0001é\"\n  },\n  \"b\": [1, 2]\n}");
  CHECK(json::read(json::write(v)).find("a")->find("s")->string() == "q\"\\\n\x01é");
  CHECK(json::read(R"("\u00e9\ud83d\ude00")").string() == "é😀");
}

TEST_CASE("json reading errors name source, line and column") {
  CHECK_THROWS_WITH(json::read("{\"a\": 1,\n \"b\" 2}", "r.json"), Catch::StartsWith("r.json:2:6: expected ':'"));
  CHECK_THROWS_WITH(json::read("[1, 2"), Catch::Contains("json:1:6: expected ',' or ']'"));
  CHECK_THROWS_WITH(json::read("[1] x"), Catch::Contains("unexpected text after the JSON value"));
  CHECK_THROWS_WITH(json::read("[01x]"), Catch::Contains("expected ',' or ']'"));
  CHECK_THROWS_AS(json::read(std::string(1000, '[')), smi::Error);
}
