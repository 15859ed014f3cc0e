// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.csv.read/write and smi.json.encode/decode/write/read
// (luax/option_schema.hpp); csv_json_doc.cpp lists their options from them.
#include <string>
#include <vector>

#include "luax/option_schema.hpp"
#include "platform/core/csv.hpp"
#include "platform/core/json.hpp"

namespace smi::bind {

struct CsvReadArgs : csv::ReadOptions {
  std::string decimal = ".";         ///< "." or "," (checked with sep by the binding)
  std::vector<std::string> strings;  ///< columns kept as text
};

struct CsvWriteArgs : csv::ReadOptions {
  std::vector<std::string> header;  ///< the column order (none: the names sorted)
};

/// encode's and write's options: the codec's, plus encode's skip.
struct JsonEncodeArgs : json::WriteOptions {
  bool skip = false;  ///< leave out what JSON cannot hold (encode only)
};

/// write's defaults differ from encode's only in the indent: a file is read by people.
struct JsonWriteArgs : JsonEncodeArgs {
  JsonWriteArgs() { indent = 2; }
};

/// decode's and read's table: null only, read by hand (the value stays on the stack).
struct JsonDecodeArgs {};

const lua::Schema<CsvReadArgs>& csv_read_schema();
const lua::Schema<CsvWriteArgs>& csv_write_schema();
const lua::Schema<JsonEncodeArgs>& json_encode_schema();
const lua::Schema<JsonWriteArgs>& json_write_schema();
/// smi.json.decode's (file = false) or smi.json.read's (file = true).
const lua::Schema<JsonDecodeArgs>& json_decode_schema(bool file);

}  // namespace smi::bind
