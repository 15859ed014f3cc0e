// SPDX-License-Identifier: MIT
// Deck templates: formats, literal rendering of hostile values, errors that name file and line.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "platform/eval/deck_template.hpp"

using namespace smi::eval;

namespace {
std::string error_of(const DeckTemplate& t, const DeckValues& v) {
  try {
    t.render(v);
  } catch (const TemplateError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("placeholders take printf formats and default to the shortest exact text") {
  const DeckTemplate t("E = {{E:%.6E}}\nnu={{ nu }}\nn = {{n:%5d}}\nname = {{label}}\n", "deck.tpl");
  const std::string out = t.render({{"E", DeckValue::num(205000)}, {"nu", DeckValue::num(0.1)},
                                    {"n", DeckValue::num(3)}, {"label", DeckValue::str("rigid")}});
  CHECK(out == "E = 2.050000E+05\nnu=0.1\nn =     3\nname = rigid\n");
  // The default text reads back as the same double (0.1 + 0.2 is not 0.3 in binary).
  const std::string s = DeckTemplate("{{x}}", "t").render({{"x", DeckValue::num(0.1 + 0.2)}});
  CHECK(std::strtod(s.c_str(), nullptr) == 0.1 + 0.2);
  CHECK(t.names() == std::vector<std::string>{"E", "nu", "n", "label"});
}

TEST_CASE("values with shell syntax are rendered literally") {
  const std::string hostile = "x;rm -rf / $(touch pwned) `id` && echo ${HOME} | cat > /tmp/x";
  const DeckTemplate t("label = {{label}}\n", "deck.tpl");
  CHECK(t.render({{"label", DeckValue::str(hostile)}}) == "label = " + hostile + "\n");
}

TEST_CASE("template errors name the file, the line and the placeholder") {
  const DeckTemplate t("a = {{a}}\n\nb = {{b}}\n", "decks/column.tpl");
  const std::string e = error_of(t, {{"a", DeckValue::num(1)}});
  CHECK(e.find("decks/column.tpl") != std::string::npos);
  CHECK(e.find("line 3") != std::string::npos);
  CHECK(e.find("{{b}}") != std::string::npos);
  CHECK(e.find("(a)") != std::string::npos);  // lists what it knows

  CHECK_THROWS_WITH(DeckTemplate("x\ny = {{y\n", "t.tpl"), Catch::Contains("t.tpl' line 2") && Catch::Contains("closing"));
  CHECK_THROWS_WITH(DeckTemplate("{{2x}}", "t.tpl"), Catch::Contains("not a name"));
  CHECK_THROWS_WITH(DeckTemplate("{{x:%s}}", "t.tpl"), Catch::Contains("format '%s'"));
  CHECK_THROWS_WITH(DeckTemplate("{{x:%n}}", "t.tpl"), Catch::Contains("format '%n'"));
  const DeckTemplate d("n = {{n:%d}}", "t.tpl");
  CHECK(error_of(d, {{"n", DeckValue::num(2.5)}}).find("not an integer") != std::string::npos);
  CHECK(error_of(d, {{"n", DeckValue::str("two")}}).find("string 'two'") != std::string::npos);
  const DeckTemplate s("s = {{s}}", "t.tpl");
  CHECK(error_of(s, {{"s", DeckValue::str("a\nE = 0")}}).find("line break") != std::string::npos);
  CHECK(error_of(s, {{"s", DeckValue::num(std::nan(""))}}).find("finite") != std::string::npos);
}
