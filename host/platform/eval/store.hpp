// SPDX-License-Identifier: MIT
#pragma once
// The evaluation store: one SQLite database (write-ahead log) holding every finished solver
// evaluation, keyed by a content hash of what determines its result (rendered deck, program,
// version, command line, extra files). Each record is committed on its own as soon as its run
// ends, so a study killed with SIGKILL loses only the runs that had not finished; running the
// study again finds the rest. synchronous=NORMAL under WAL is durable against a crash of the
// process (not against power loss), which is the failure this store guards against, at a
// fraction of a millisecond per record.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "platform/core/errors.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace smi::eval {

using NamedValues = std::vector<std::pair<std::string, double>>;

struct Record {
  std::string key;
  std::string model;      // the model's name (informative)
  std::string program;    // program name as given
  std::string version;    // the version that went into the key
  NamedValues inputs;
  NamedValues outputs;    // empty for a failure
  bool ok = false;
  std::string reason;     // why it failed ("" when ok)
  double duration = 0;    // seconds of the run (last attempt)
  int attempts = 1;
  std::string stdout_tail, stderr_tail;
  std::string workdir;
};

struct Timing {
  long count = 0;      // successful runs on record
  double mean = 0;     // their mean duration, seconds
};

/// The key scheme of this build, kept in the store as PRAGMA user_version (see Evaluator).
inline constexpr long kKeyVersion = 2;

class Store {
 public:
  /// Opens (creating if needed, unless read_only) the store at `path` (a symlink as last
  /// component is refused). A read-only store is never written; `immutable` (a --store) also
  /// makes no -shm/-wal beside it and reads the file as a snapshot. A store of another key scheme (an older smi-lua) is refused with a
  /// message saying so. Throws smi::Error naming the path and SQLite's message.
  Store(const std::string& path, bool read_only, bool immutable = false);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  /// The record for `key`, if any (successful or failed).
  std::optional<Record> find(const std::string& key);
  /// Inserts or replaces the record for r.key in its own transaction. A failure never replaces
  /// a success already stored under the same key.
  void put(const Record& r);
  /// Stored timings of successful runs of `program` at `version` (for --dry-run ETAs).
  Timing timing(const std::string& program, const std::string& version);
  /// Number of records (all statuses).
  long count();

  const std::string& path() const { return path_; }
  bool read_only() const { return read_only_; }
  /// The open database, for tables kept beside the records (eval/pending.hpp).
  sqlite3* handle() const { return db_; }

 private:
  void exec(const char* sql);
  void check_key_version(bool writable);
  [[noreturn]] void fail(const char* what);
  sqlite3* db_ = nullptr;
  sqlite3_stmt* find_ = nullptr;
  sqlite3_stmt* put_ = nullptr;
  std::string path_;
  bool read_only_;
  int dir_fd_ = -1;  // the store's folder, held open: SQLite reaches the files through it (store.cpp)
};

/// "name\tvalue\n" lines with values in shortest round-trip form ("nan", "inf" allowed).
std::string encode_values(const NamedValues& v);
NamedValues decode_values(const std::string& s);

}  // namespace smi::eval
