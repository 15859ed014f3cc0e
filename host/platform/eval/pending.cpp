// SPDX-License-Identifier: MIT
#include "platform/eval/pending.hpp"

#include <fmt/format.h>
#include <sqlite3.h>

#include "platform/core/errors.hpp"

namespace smi::eval {
namespace {

/// A prepared statement that finalizes itself.
struct Stmt {
  sqlite3_stmt* s = nullptr;
  Stmt(sqlite3* db, const char* sql) {
    if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK)
      throw Error(fmt::format("evaluation store: pending table: {}", sqlite3_errmsg(db)));
  }
  ~Stmt() { sqlite3_finalize(s); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  void text(int i, const std::string& v) { sqlite3_bind_text(s, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT); }
  std::string col(int i) {
    const unsigned char* t = sqlite3_column_text(s, i);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
};

}  // namespace

PendingTable::PendingTable(sqlite3* db) : db_(db) {
  exec("CREATE TABLE IF NOT EXISTS pending (key TEXT PRIMARY KEY, job_name TEXT NOT NULL, job_id TEXT NOT NULL, "
       "array_index INTEGER NOT NULL, attempt INTEGER NOT NULL, workdir TEXT NOT NULL)");
}

void PendingTable::exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errmsg(db_);
    sqlite3_free(err);
    throw Error(fmt::format("evaluation store: pending table: {}", msg));
  }
}

std::optional<PendingRun> PendingTable::find(const std::string& key) {
  Stmt q(db_, "SELECT job_name, job_id, array_index, attempt, workdir FROM pending WHERE key = ?");
  q.text(1, key);
  if (sqlite3_step(q.s) != SQLITE_ROW) return std::nullopt;
  PendingRun r;
  r.key = key;
  r.job_name = q.col(0);
  r.job_id = q.col(1);
  r.array_index = sqlite3_column_int(q.s, 2);
  r.attempt = sqlite3_column_int(q.s, 3);
  r.workdir = q.col(4);
  return r;
}

void PendingTable::put(const std::vector<PendingRun>& rows) {
  exec("BEGIN IMMEDIATE");
  try {
    Stmt q(db_, "INSERT OR REPLACE INTO pending VALUES (?, ?, ?, ?, ?, ?)");
    for (const auto& r : rows) {
      sqlite3_reset(q.s);
      q.text(1, r.key);
      q.text(2, r.job_name);
      q.text(3, r.job_id);
      sqlite3_bind_int(q.s, 4, r.array_index);
      sqlite3_bind_int(q.s, 5, r.attempt);
      q.text(6, r.workdir);
      if (sqlite3_step(q.s) != SQLITE_DONE) throw Error(fmt::format("evaluation store: pending table: {}", sqlite3_errmsg(db_)));
    }
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

void PendingTable::set_job_id(const std::string& job_name, const std::string& job_id) {
  Stmt q(db_, "UPDATE pending SET job_id = ? WHERE job_name = ?");
  q.text(1, job_id);
  q.text(2, job_name);
  if (sqlite3_step(q.s) != SQLITE_DONE) throw Error(fmt::format("evaluation store: pending table: {}", sqlite3_errmsg(db_)));
}

void PendingTable::erase(const std::string& key, const std::string& job_id) {
  Stmt q(db_, "DELETE FROM pending WHERE key = ? AND job_id = ?");
  q.text(1, key);
  q.text(2, job_id);
  sqlite3_step(q.s);
}

long PendingTable::count() {
  Stmt q(db_, "SELECT count(*) FROM pending");
  return sqlite3_step(q.s) == SQLITE_ROW ? static_cast<long>(sqlite3_column_int64(q.s, 0)) : 0;
}

}  // namespace smi::eval
