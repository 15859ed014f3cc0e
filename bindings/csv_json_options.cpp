// SPDX-License-Identifier: MIT
// The option schemas of the CSV and JSON functions (csv_json_options.hpp). Defaults: the structs'.
#include "bindings/csv_json_options.hpp"

#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind {

using namespace smi::lua;

namespace {

/// sep: one character other than a quote or a newline.
template <class S>
Option<S> sep_option(const char* doc) {
  return {"sep", doc,
          [](lua_State* L, int v, S& s) {
            const std::string x = schema_detail::to_string(L, v, "sep");
            if (x.size() != 1 || x[0] == '"' || x[0] == '\n' || x[0] == '\r')
              throw Error("option 'sep' must be one character other than a quote or a newline, got '" + x + "'");
            s.sep = x[0];
          },
          [](const S& s) { return schema_detail::show_string(std::string(1, s.sep)); }, {}};
}

/// A list of names (strings, header): none unless given.
template <class S>
Option<S> names_option(const char* key, std::vector<std::string> S::*m, const char* doc, const char* none) {
  return {key, doc, [=](lua_State* L, int v, S& s) { s.*m = lua::to_strings(L, v, (std::string("option '") + key + "'").c_str()); },
          [=](const S&) { return std::string(none); }, {}};
}

template <class S>
std::vector<Option<S>> encode_options(bool encode) {
  std::vector<Option<S>> o{
      integer<S>("indent", &json::WriteOptions::indent, between(0, 16),  // literal: the deepest indent
                 encode ? "spaces per level, 0..16; 0 writes one line" : "spaces per level, 0..16"),
      choice<S>("nonfinite", &json::WriteOptions::non_finite,
                Names<json::NonFinite>{{"refuse", json::NonFinite::Refuse}, {"encode", json::NonFinite::Encode}},
                encode ? "or \"encode\": inf as 1e999, -inf as -1e999, NaN as null" : "as smi.json.encode")};
  if (encode) o.push_back(boolean<S>("skip", &JsonEncodeArgs::skip, "leave out what JSON cannot hold; their paths are the second result"));
  o.push_back(string<S>("root", &json::WriteOptions::root, {}, "the name of the value in error paths"));
  return o;
}

}  // namespace

const Schema<CsvReadArgs>& csv_read_schema() {
  using S = CsvReadArgs;
  static const Schema<S> s("smi.csv.read", std::vector<Option<S>>{
      sep_option<S>("the separator, one character other than a quote or a newline"),
      string<S>("decimal", &S::decimal, {}, "the decimal mark of the numbers: \".\" or \",\" (with sep = \";\" or \"\\t\")"),
      names_option<S>("strings", &S::strings, "names of columns to keep as text even when they look numeric (IDs)", "{}"),
  });
  return s;
}

const Schema<CsvWriteArgs>& csv_write_schema() {
  using S = CsvWriteArgs;
  static const Schema<S> s("smi.csv.write", std::vector<Option<S>>{
      sep_option<S>("the separator"),
      names_option<S>("header", &S::header, "the column order, a list of names (default: the names sorted)", "nil"),
  });
  return s;
}

const Schema<JsonEncodeArgs>& json_encode_schema() {
  static const Schema<JsonEncodeArgs> s("smi.json.encode", encode_options<JsonEncodeArgs>(true));
  return s;
}

const Schema<JsonWriteArgs>& json_write_schema() {
  static const Schema<JsonWriteArgs> s("smi.json.write", encode_options<JsonWriteArgs>(false));
  return s;
}

const Schema<JsonDecodeArgs>& json_decode_schema(bool file) {
  using S = JsonDecodeArgs;
  static const Schema<S> d("smi.json.decode", std::vector<Option<S>>{by_hand<S>(
                                                   "null", "smi.json.null", "what null reads as (0/0 for files written with nonfinite = \"encode\")")});
  static const Schema<S> r("smi.json.read", std::vector<Option<S>>{by_hand<S>("null", "smi.json.null", "what null reads as (as smi.json.decode)")});
  return file ? r : d;
}

}  // namespace smi::bind
