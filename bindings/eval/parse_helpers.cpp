// SPDX-License-Identifier: MIT
// Helpers for output parsers: h.read, h.exists, h.regex, h.regex_all, h.csv, h.f06, h.ccx_dat. A parser
// receives them bound to its run's work directory (h.f06("column.f06")); smi.model.parse holds
// the same functions for any allowed path. Every read goes through the sandbox.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>

#include "bindings/eval/model.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "platform/eval/ccx_dat.hpp"
#include "platform/eval/f06.hpp"
#include "platform/eval/text_parsers.hpp"

namespace smi::bind::eval {
namespace {

namespace se = smi::eval;

/// The file argument joined to the bound directory (upvalue 1, "" for none). Stack: [file, ...].
std::string path_arg(lua_State* L) {
  const char* file = luaL_checkstring(L, 1);
  const char* dir = lua_tostring(L, lua_upvalueindex(1));
  std::string p = file;
  if (dir && *dir && !std::filesystem::path(p).is_absolute()) p = (std::filesystem::path(dir) / p).string();
  return p;
}

/// The text of an output file, opened through the sandbox (what is read is what was checked).
/// A missing file is a parse failure of that run, named as such.
std::string read_output(lua_State* L, const std::string& p) {
  try {
    return lua::read_checked(lua::policy(L).open_read(p), p);
  } catch (const lua::FileError& e) {
    throw se::ParseError(fmt::format("output file '{}' is missing or unreadable: {}", p, std::strerror(e.err)));
  }
}

int h_read(lua_State* L) {
  const std::string p = path_arg(L);
  return lua::protect(L, "smi.model.parse.read", [&] {
    const std::string t = read_output(L, p);
    lua_pushlstring(L, t.data(), t.size());
    return 1;
  });
}

int h_exists(lua_State* L) {
  const std::string p = path_arg(L);
  bool exists = false;
  lua::protect(L, "smi.model.parse.exists", [&] {
    try {
      (void)lua::policy(L).open_read(p);  // a denial raises; a readable regular file exists
      exists = true;
    } catch (const lua::FileError& e) {
      exists = e.err == EISDIR || e.err == EINVAL;  // a folder or another non-regular entry exists too
    }
    return 0;
  });
  lua_pushboolean(L, exists);
  return 1;
}

int h_regex(lua_State* L) {
  const std::string p = path_arg(L);
  const std::string pattern = luaL_checkstring(L, 2);
  return lua::protect(L, "smi.model.parse.regex", [&] {
    lua_pushnumber(L, se::regex_number(read_output(L, p), pattern, p));
    return 1;
  });
}

int h_regex_all(lua_State* L) {
  const std::string p = path_arg(L);
  const std::string pattern = luaL_checkstring(L, 2);
  return lua::protect(L, "smi.model.parse.regex_all", [&] {
    lua::push_vec(L, se::regex_numbers(read_output(L, p), pattern, p));
    return 1;
  });
}

int h_csv(lua_State* L) {
  const std::string p = path_arg(L);
  const std::string column = luaL_checkstring(L, 2);
  return lua::protect(L, "smi.model.parse.csv", [&] {
    lua::push_vec(L, se::csv_column(read_output(L, p), column, p));
    return 1;
  });
}

/// h.f06(file) -> {mode, order, eigenvalue, radians, cycles, mass, stiffness (smi.vec each),
///   direction = {...} (per label row), labels = {{mode, cycles, direction, paper, participation}},
///   paper = {[n] = {mode, direction, hz}}, paper_hz = smi.vec (paper modes 1..k in order)}
int h_f06(lua_State* L) {
  const std::string p = path_arg(L);
  return lua::protect(L, "smi.model.parse.f06", [&] {
    const se::F06Result r = se::parse_f06(read_output(L, p), p);
    const auto n = static_cast<Eigen::Index>(r.eigen.size());
    Eigen::MatrixXd cols(n, 7);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto& e = r.eigen[static_cast<std::size_t>(i)];
      cols.row(i) << e.mode, e.order, e.eigenvalue, e.radians, e.cycles, e.mass, e.stiffness;
    }
    lua_createtable(L, 0, 12);
    const char* names[] = {"mode", "order", "eigenvalue", "radians", "cycles", "mass", "stiffness"};
    for (int j = 0; j < 7; ++j) lua::set_vec(L, names[j], cols.col(j));
    lua_createtable(L, static_cast<int>(r.labels.size()), 0);  // labels
    lua_createtable(L, static_cast<int>(r.labels.size()), 0);  // direction
    for (std::size_t i = 0; i < r.labels.size(); ++i) {
      const auto& l = r.labels[i];
      lua_createtable(L, 0, 5);
      lua::set_integer(L, "mode", l.mode);
      lua::set_number(L, "cycles", l.cycles);
      lua::set_string(L, "direction", l.direction);
      if (l.paper > 0) lua::set_integer(L, "paper", l.paper);
      lua::set_vec(L, "participation", Eigen::Map<const Eigen::VectorXd>(l.participation, 6));
      lua_rawseti(L, -3, static_cast<lua_Integer>(i + 1));
      lua_pushstring(L, l.direction.c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -3, "direction");
    lua_setfield(L, -2, "labels");
    lua_newtable(L);
    Eigen::VectorXd hz(static_cast<Eigen::Index>(r.paper.size()));
    for (std::size_t i = 0; i < r.paper.size(); ++i) {
      const auto& pm = r.paper[i];
      hz[static_cast<Eigen::Index>(i)] = pm.hz;
      lua_createtable(L, 0, 3);
      lua::set_integer(L, "mode", pm.mode);
      lua::set_string(L, "direction", pm.direction);
      lua::set_number(L, "hz", pm.hz);
      lua_rawseti(L, -2, pm.paper);
    }
    lua_setfield(L, -2, "paper");
    lua::set_vec(L, "paper_hz", std::move(hz));
    return 1;
  });
}

/// h.ccx_dat(file) -> {mode, eigenvalue, radians, cycles, imaginary (smi.vec each; cycles in Hz),
///   blocks = {{name, set, time, mode, columns = {names}, rows = smi.mat, [column] = smi.vec}}}
int h_ccx_dat(lua_State* L) {
  const std::string p = path_arg(L);
  return lua::protect(L, "smi.model.parse.ccx_dat", [&] {
    const se::CcxDat r = se::parse_ccx_dat(read_output(L, p), p);
    const auto n = static_cast<Eigen::Index>(r.eigen.size());
    Eigen::MatrixXd cols(n, 5);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto& e = r.eigen[static_cast<std::size_t>(i)];
      cols.row(i) << e.mode, e.eigenvalue, e.radians, e.cycles, e.imaginary;
    }
    lua_createtable(L, 0, 6);
    const char* names[] = {"mode", "eigenvalue", "radians", "cycles", "imaginary"};
    for (int j = 0; j < 5; ++j) lua::set_vec(L, names[j], cols.col(j));
    lua_createtable(L, static_cast<int>(r.blocks.size()), 0);
    for (std::size_t b = 0; b < r.blocks.size(); ++b) {
      const auto& blk = r.blocks[b];
      lua_createtable(L, 0, static_cast<int>(6 + blk.columns.size()));
      lua::set_string(L, "name", blk.name);
      lua::set_string(L, "set", blk.set);
      lua::set_number(L, "time", blk.time);
      lua::set_integer(L, "mode", blk.mode);
      lua_createtable(L, static_cast<int>(blk.columns.size()), 0);
      for (std::size_t j = 0; j < blk.columns.size(); ++j) {
        lua_pushstring(L, blk.columns[j].c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(j + 1));
        lua::push_vec(L, blk.rows.col(static_cast<Eigen::Index>(j)));
        lua_setfield(L, -3, blk.columns[j].c_str());  // into the block, below the columns list
      }
      lua_setfield(L, -2, "columns");
      lua::push_mat(L, blk.rows);
      lua_setfield(L, -2, "rows");
      lua_rawseti(L, -2, static_cast<lua_Integer>(b + 1));
    }
    lua_setfield(L, -2, "blocks");
    return 1;
  });
}

const luaL_Reg kHelpers[] = {{"read", h_read},   {"exists", h_exists}, {"regex", h_regex}, {"regex_all", h_regex_all},
                             {"csv", h_csv},     {"f06", h_f06},       {"ccx_dat", h_ccx_dat},
                             {nullptr, nullptr}};

}  // namespace

void push_parse_helpers(lua_State* L, const std::string& dir) {
  lua_createtable(L, 0, 7);
  lua_pushstring(L, dir.c_str());
  luaL_setfuncs(L, kHelpers, 1);  // each helper gets the directory as upvalue 1
  lua_pushstring(L, dir.c_str());
  lua_setfield(L, -2, "dir");
}

}  // namespace smi::bind::eval
