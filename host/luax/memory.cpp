// SPDX-License-Identifier: MIT
#include "luax/memory.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <unistd.h>

#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::lua {
namespace {

const char kBudgetKey = 0;
constexpr std::size_t kStepBytes = 256u << 10;  // report to the collector every 256 KB of boxes

MemoryBudget* budget(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kBudgetKey);
  auto* b = static_cast<MemoryBudget*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return b;
}

double mb(double bytes) { return bytes / (1024.0 * 1024.0); }

double physical_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0;
}

std::size_t in_use(const MemoryBudget& b) { return (b.lua_used ? *b.lua_used : 0) + b.external; }

}  // namespace

void set_memory_budget(lua_State* L, MemoryBudget* b) {
  lua_pushlightuserdata(L, b);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kBudgetKey);
}

namespace {

/// "" when `count` values of `elem_bytes` fit, else why not (the message both checks raise).
std::string alloc_refusal(lua_State* L, double count, std::size_t elem_bytes, const char* what) {
  const double bytes = count * static_cast<double>(elem_bytes);
  const double phys = physical_bytes();
  char msg[512];  // lua_pushfstring has no precision: format here
  if (!(bytes >= 0) || (phys > 0 && bytes > phys)) {  // NaN counts too
    std::snprintf(msg, sizeof msg, "%s: %.0f values need %.0f MB, more than this machine's memory (%.0f MB)", what,
                  count, mb(bytes), mb(phys));
    return msg;
  }
  MemoryBudget* b = budget(L);
  if (!b || !b->limit) return "";
  if (static_cast<double>(in_use(*b)) + bytes > static_cast<double>(b->limit)) {
    lua_gc(L, LUA_GCCOLLECT);  // garbage vecs may hold the room
    if (static_cast<double>(in_use(*b)) + bytes > static_cast<double>(b->limit)) {
      std::snprintf(msg, sizeof msg,
                 "memory limit exceeded: %s needs %.1f MB; in use %.1f MB (Lua heap %.1f MB, vec/mat/Kriging data %.1f MB) "
                 "of --max-memory %.0f MB; raise --max-memory or drop references to large objects",
                 what, mb(bytes), mb(static_cast<double>(in_use(*b))), mb(b->lua_used ? static_cast<double>(*b->lua_used) : 0),
                 mb(static_cast<double>(b->external)), mb(static_cast<double>(b->limit)));
      return msg;
    }
  }
  return "";
}

}  // namespace

void check_alloc(lua_State* L, double count, std::size_t elem_bytes, const char* what) {
  char msg[600];
  {
    const std::string why = alloc_refusal(L, count, elem_bytes, what);
    if (why.empty()) return;
    std::snprintf(msg, sizeof msg, "%s", why.c_str());
  }
  luaL_error(L, "%s", msg);
}

void require_room(lua_State* L, double count, std::size_t elem_bytes, const char* what) {
  const std::string why = alloc_refusal(L, count, elem_bytes, what);
  if (!why.empty()) throw Error(why);
}

void account_bytes(lua_State* L, std::size_t bytes, const char* what) {
  MemoryBudget* b = budget(L);
  if (!b) return;
  if (b->limit) check_alloc(L, static_cast<double>(bytes), 1, what);
  b->external += bytes;
  b->since_step += bytes;
  if (b->since_step >= kStepBytes) {
    // Tell the collector as if Lua had allocated these bytes: garbage boxes get collected at
    // the pace their real size calls for (Lua 5.4 has no external-memory API; a step with a
    // size is the documented way to advance the collector by that much).
    const int kb = static_cast<int>(std::min<std::size_t>(b->since_step >> 10, 1u << 30));
    b->since_step = 0;
    lua_gc(L, LUA_GCSTEP, kb);
  }
}

void release_bytes(lua_State* L, std::size_t bytes) {
  MemoryBudget* b = budget(L);
  if (!b) return;
  b->external = b->external > bytes ? b->external - bytes : 0;
}

}  // namespace smi::lua
