// SPDX-License-Identifier: MIT
// smi.csv: comma-separated tables with a header row, columns by name.
//   local d, header, notes = smi.csv.read(path [, {sep = ",", decimal = ".", strings = {"name", ...}}])
//       d.<column> is a smi.vec when every cell of the column is a number, a table of strings
//       otherwise; header lists the column names in file order; notes.warnings lists data
//       sanity warnings (duplicated rows, also printed on stderr unless quiet) for a report and
//       notes.duplicates the {first line, repeated line} pairs. A UTF-8 BOM is dropped; a file
//       with a header but no data rows is an error.
//   smi.csv.write(path, t [, {header = {...}, sep = ","}])
//       t.<column> a vec or a table of numbers/strings, all the same length; the header row
//       follows opts.header, else the column names sorted.
// The text is read and written by the one CSV codec (core/csv.hpp, RFC 4180); here only the
// table logic. Both go through the sandbox policy (read / write). A bad number is reported with the file,
// line and column; numbers are written so that they read back exactly (shortest round trip).
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <set>
#include <string>
#include <variant>
#include <map>
#include <vector>

#include "bindings/csv_json_options.hpp"
#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"
#include "platform/core/csv.hpp"
#include "platform/core/number_text.hpp"

namespace smi::bind {
namespace {

using Column = std::variant<std::vector<double>, std::vector<std::string>>;

struct Table {
  std::vector<std::string> header;
  std::vector<Column> columns;
  std::vector<std::pair<long, long>> duplicates;  // (line of the first, line of the repeat)
  std::vector<long> lines;  // the file line of each data row (messages name rows by it)
};

/// A cell as a number, with ',' as the decimal mark when decimal == ','.
bool cell_number(const std::string& cell, char decimal, double& v) {
  if (decimal != ',' || cell.find('.') != std::string::npos) return csv::parse_number(cell, v);
  std::string t = cell;
  for (char& c : t)
    if (c == ',') c = '.';
  return csv::parse_number(t, v);
}

/// The column names of the header record: trimmed, none empty, none twice.
std::vector<std::string> header_names(const csv::Record& head, const std::string& file) {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < head.fields.size(); ++j) {
    std::string name = csv::trim(head.fields[j]);
    if (name.empty()) throw Error(fmt::format("line {} of {}: column {} has an empty name", head.line, file, j + 1));
    for (const auto& h : out)
      if (h == name) throw Error(fmt::format("line {} of {}: column name '{}' appears twice", head.line, file, name));
    out.push_back(std::move(name));
  }
  return out;
}

Table parse_table(const std::string& raw, char sep, char decimal, const std::string& file,
                  const std::set<std::string>& strings) {
  csv::ReadOptions ro;
  ro.sep = sep;
  const std::vector<csv::Record> recs = csv::read(raw, file, ro);
  if (recs.empty()) throw Error(fmt::format("{}: the file is empty (a header row is needed)", file));
  // A one-column header holding ';' or a tab is a file written with another separator (a
  // spreadsheet's "CSV" in a locale with decimal commas): say what the file uses.
  const std::string hint = csv::sniff(raw, sep);
  if (recs[0].fields.size() == 1 && !hint.empty())
    throw Error(fmt::format("line {} of {}: {} (the header '{}' reads as one column name)", recs[0].line, file, hint,
                            csv::trim(recs[0].fields[0]).substr(0, 60)));  // literal: the excerpt a message quotes
  Table t;
  t.header = header_names(recs[0], file);
  const std::size_t ncol = t.header.size();
  if (recs.size() == 1) {
    std::string names;
    for (const auto& h : t.header) names += (names.empty() ? "" : ", ") + h;
    throw Error(fmt::format("{}: only a header row (columns: {}) and no data rows; add the data below line {}", file,
                            names, recs[0].line));
  }
  for (std::size_t r = 1; r < recs.size(); ++r)
    if (recs[r].fields.size() != ncol)
      throw Error(fmt::format("line {} of {}: {} fields, but the header has {} columns{}", recs[r].line, file,
                              recs[r].fields.size(), ncol, hint.empty() ? "" : "; " + hint));
  for (std::size_t j = 0; j < ncol; ++j) {
    // A column is numeric when its first non-empty cell is a number (and it is not listed in
    // opts.strings); from then on every cell must be one.
    bool numeric = false;
    if (!strings.count(t.header[j]))
      for (std::size_t r = 1; r < recs.size(); ++r) {
        if (csv::trim(recs[r].fields[j]).empty()) continue;
        double v;
        numeric = cell_number(recs[r].fields[j], decimal, v);
        if (!numeric && decimal != ',' && csv::decimal_comma(recs[r].fields[j]))
          throw Error(fmt::format("line {} of {}: column {} ('{}'): '{}' is written with a decimal comma: pass decimal = ',' "
                                  "or save the file with '.' decimals (or read the column as text with "
                                  "{{strings = {{\"{}\"}}}})",
                                  recs[r].line, file, j + 1, t.header[j], recs[r].fields[j], t.header[j]));
        break;
      }
    if (numeric) {
      std::vector<double> col;
      col.reserve(recs.size() - 1);
      for (std::size_t r = 1; r < recs.size(); ++r) {
        double v = 0;
        if (!cell_number(recs[r].fields[j], decimal, v)) {
          if (decimal != ',' && csv::decimal_comma(recs[r].fields[j]))
            throw Error(fmt::format("line {} of {}: column {} ('{}'): '{}' is written with a decimal comma: pass decimal = ',' "
                                    "or save the file with '.' decimals",
                                    recs[r].line, file, j + 1, t.header[j], recs[r].fields[j]));
          throw Error(fmt::format(
              "line {} of {}: column {} ('{}'): bad number '{}' (the column holds numbers above; fix the cell, or "
              "read the column as text with {{strings = {{\"{}\"}}}})",
              recs[r].line, file, j + 1, t.header[j], recs[r].fields[j], t.header[j]));
        }
        col.push_back(v);
      }
      t.columns.emplace_back(std::move(col));
    } else {
      std::vector<std::string> col;
      for (std::size_t r = 1; r < recs.size(); ++r) col.push_back(recs[r].fields[j]);
      t.columns.emplace_back(std::move(col));
    }
  }
  // Rows entered twice weigh double in every fit and every validation: say so (not an error,
  // repeated measurements can be real).
  std::map<std::vector<std::string>, long> first_line;
  for (std::size_t r = 1; r < recs.size(); ++r) t.lines.push_back(recs[r].line);
  for (std::size_t r = 1; r < recs.size(); ++r) {
    std::vector<std::string> key;
    for (const auto& f : recs[r].fields) key.push_back(csv::trim(f));
    const auto [it, fresh] = first_line.emplace(std::move(key), recs[r].line);
    if (!fresh) t.duplicates.emplace_back(it->second, recs[r].line);
  }
  return t;
}

/// smi.csv.read(path [, opts]) -> columns, header
int csv_read(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  const CsvReadArgs opts = csv_read_schema().read(L, 2);
  const std::set<std::string> strings(opts.strings.begin(), opts.strings.end());
  return lua::protect(L, "smi.csv.read", [&] {
    const char sep = opts.sep;
    const std::string& decimal = opts.decimal;
    if (decimal != "." && decimal != ",") throw Error("option 'decimal' must be '.' or ',', got '" + decimal + "'");
    if (decimal == "," && sep == ',') throw Error("decimal = ',' needs another separator: pass sep = ';' (or '\\t')");
    const lua::CheckedFile f = lua::policy(L).open_read(path);
    const Table t = parse_table(lua::read_checked(f, path), sep, decimal[0], path, strings);
    lua_createtable(L, 0, static_cast<int>(t.header.size()));  // stack: [..., columns]
    for (std::size_t j = 0; j < t.header.size(); ++j) {
      if (const auto* num = std::get_if<std::vector<double>>(&t.columns[j])) {
        lua::push_vec(L, Eigen::Map<const Eigen::VectorXd>(num->data(), static_cast<Eigen::Index>(num->size())));
      } else {
        const auto& str = std::get<std::vector<std::string>>(t.columns[j]);
        lua_createtable(L, static_cast<int>(str.size()), 0);
        for (std::size_t r = 0; r < str.size(); ++r) {
          lua_pushlstring(L, str[r].data(), str[r].size());
          lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
        }
      }
      lua_setfield(L, -2, t.header[j].c_str());
    }
    lua_createtable(L, static_cast<int>(t.header.size()), 0);  // stack: [..., columns, header]
    for (std::size_t j = 0; j < t.header.size(); ++j) {
      lua_pushstring(L, t.header[j].c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(j + 1));
    }
    // stack: [..., columns, header, notes]: notes.warnings (text, for a report) and
    // notes.duplicates ({first_line, repeat_line} pairs)
    lua_createtable(L, 0, 2);
    lua_createtable(L, 0, 0);
    lua_createtable(L, static_cast<int>(t.duplicates.size()), 0);
    std::string lines;
    for (std::size_t k = 0; k < t.duplicates.size(); ++k) {
      lua_createtable(L, 2, 0);
      lua_pushinteger(L, t.duplicates[k].first);
      lua_rawseti(L, -2, 1);
      lua_pushinteger(L, t.duplicates[k].second);
      lua_rawseti(L, -2, 2);
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      if (k < 5) lines += fmt::format("{}line {} repeats line {}", k ? ", " : "", t.duplicates[k].second, t.duplicates[k].first);
    }
    lua_setfield(L, -3, "duplicates");
    lua_createtable(L, static_cast<int>(t.lines.size()), 0);  // notes.lines[i]: the file line of data row i
    for (std::size_t k = 0; k < t.lines.size(); ++k) {
      lua_pushinteger(L, t.lines[k]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
    lua_setfield(L, -3, "lines");
    if (!t.duplicates.empty()) {
      const std::string w = fmt::format(
          "{}: {} duplicated data row{} ({}{}); a row entered twice counts twice in every fit and validation: "
          "remove the copies unless they are real repeated measurements",
          path, t.duplicates.size(), t.duplicates.size() == 1 ? "" : "s", lines, t.duplicates.size() > 5 ? ", ..." : "");
      lua_pushstring(L, w.c_str());
      lua_rawseti(L, -2, 1);
      lua::warn(L, "smi.csv.read", w);  // printed unless --quiet, and in smi.warnings()
    }
    lua_setfield(L, -2, "warnings");
    return 3;
  });
}

std::string format_number(lua_State* L, int idx) {
  if (lua_isinteger(L, idx)) return std::to_string(lua_tointeger(L, idx));
  return number_text(lua_tonumber(L, idx));  // shortest text that reads back exactly
}

/// smi.csv.write(path, t [, opts]): columns by name, header row first.
int csv_write(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  const CsvWriteArgs opts = csv_write_schema().read(L, 3);
  std::vector<std::string> header = opts.header;
  if (header.empty()) {
    lua_pushnil(L);
    while (lua_next(L, 2)) {
      lua_pop(L, 1);
      if (lua_type(L, -1) != LUA_TSTRING)
        luaL_error(L, "smi.csv.write: column keys must be names (strings), got a %s key", luaL_typename(L, -1));
      header.emplace_back(lua_tostring(L, -1));
    }
    std::sort(header.begin(), header.end());
  }
  if (header.empty()) luaL_error(L, "smi.csv.write: the table has no columns");
  const char sep = opts.sep;
  // Render every column to text (raises on a bad cell, before the file is touched).
  std::vector<std::vector<std::string>> cols;
  for (const auto& name : header) {
    std::vector<std::string> cells;
    lua_getfield(L, 2, name.c_str());
    if (const Eigen::VectorXd* v = lua::test_vec(L, -1)) {
      for (Eigen::Index i = 0; i < v->size(); ++i) {
        lua_pushnumber(L, (*v)[i]);
        cells.push_back(format_number(L, -1));
        lua_pop(L, 1);
      }
    } else if (lua_istable(L, -1)) {
      const lua_Integer n = luaL_len(L, -1);
      for (lua_Integer i = 1; i <= n; ++i) {
        const int t = lua_rawgeti(L, -1, i);
        if (t == LUA_TNUMBER)
          cells.push_back(format_number(L, -1));
        else if (t == LUA_TSTRING)
          cells.push_back(lua_tostring(L, -1));
        else
          luaL_error(L, "smi.csv.write: column '%s'[%d] must be a number or a string, got %s", name.c_str(),
                     static_cast<int>(i), luaL_typename(L, -1));
        lua_pop(L, 1);
      }
    } else {
      luaL_error(L, "smi.csv.write: column '%s' must be a smi.vec or a table, got %s", name.c_str(),
                 luaL_typename(L, -1));
    }
    lua_pop(L, 1);
    if (!cols.empty() && cells.size() != cols.front().size())
      luaL_error(L, "smi.csv.write: column '%s' has %d values but column '%s' has %d; columns need equal lengths",
                 name.c_str(), static_cast<int>(cells.size()), header.front().c_str(),
                 static_cast<int>(cols.front().size()));
    cols.push_back(std::move(cells));
  }
  return lua::protect(L, "smi.csv.write", [&] {
    const std::string text = csv::write(header, cols, sep);
    const lua::CheckedFile f = lua::policy(L).open_write(path, O_WRONLY | O_CREAT | O_TRUNC);
    if (!pathwalk::write_all(f.fd.get(), text))
      throw Error(fmt::format("writing '{}' failed: {}", path, std::strerror(errno)));
    return 0;
  });
}

const luaL_Reg kFunctions[] = {{"read", csv_read}, {"write", csv_write}, {nullptr, nullptr}};

}  // namespace

void open_csv(lua_State* L) {
  lua_newtable(L);  // stack: [smi, csv]
  luaL_setfuncs(L, kFunctions, 0);
  lua_setfield(L, -2, "csv");
}

}  // namespace smi::bind
