// SPDX-License-Identifier: MIT
#include "platform/eval/store.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <filesystem>
#include <fmt/format.h>
#include <sqlite3.h>

namespace smi::eval {
namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS evaluations(
  key         TEXT PRIMARY KEY,
  model       TEXT NOT NULL,
  program     TEXT NOT NULL,
  version     TEXT NOT NULL,
  inputs      TEXT NOT NULL,
  outputs     TEXT NOT NULL,
  status      TEXT NOT NULL CHECK (status IN ('ok', 'failed')),
  reason      TEXT NOT NULL,
  duration    REAL NOT NULL,
  attempts    INTEGER NOT NULL,
  stdout_tail TEXT NOT NULL,
  stderr_tail TEXT NOT NULL,
  workdir     TEXT NOT NULL,
  created     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')));
CREATE INDEX IF NOT EXISTS evaluations_program ON evaluations(program, version, status);
)sql";

// A success is never overwritten by a failure under the same key (a flaky rerun must not erase
// a good result another study may rely on).
constexpr const char* kPut = R"sql(
INSERT INTO evaluations(key, model, program, version, inputs, outputs, status, reason, duration, attempts,
                        stdout_tail, stderr_tail, workdir)
VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13)
ON CONFLICT(key) DO UPDATE SET
  model = excluded.model, inputs = excluded.inputs, outputs = excluded.outputs, status = excluded.status,
  reason = excluded.reason, duration = excluded.duration, attempts = excluded.attempts,
  stdout_tail = excluded.stdout_tail, stderr_tail = excluded.stderr_tail, workdir = excluded.workdir,
  created = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
WHERE evaluations.status <> 'ok' OR excluded.status = 'ok';
)sql";

constexpr const char* kFind =
    "SELECT key, model, program, version, inputs, outputs, status, reason, duration, attempts, "
    "stdout_tail, stderr_tail, workdir FROM evaluations WHERE key = ?1";

std::string column_text(sqlite3_stmt* s, int i) {
  const auto* t = sqlite3_column_text(s, i);
  return t ? reinterpret_cast<const char*>(t) : "";
}

/// Resets a statement when it goes out of scope, whatever happened in between.
struct Reset {
  sqlite3_stmt* s;
  ~Reset() {
    sqlite3_reset(s);
    sqlite3_clear_bindings(s);
  }
};

}  // namespace

std::string encode_values(const NamedValues& v) {
  std::string s;
  for (const auto& [name, value] : v) s += fmt::format("{}\t{}\n", name, value);
  return s;
}

NamedValues decode_values(const std::string& s) {
  NamedValues out;
  std::size_t pos = 0;
  while (pos < s.size()) {
    const std::size_t eol = s.find('\n', pos);
    const std::string line = s.substr(pos, eol == std::string::npos ? std::string::npos : eol - pos);
    pos = eol == std::string::npos ? s.size() : eol + 1;
    const std::size_t tab = line.find('\t');
    if (tab == std::string::npos) continue;
    out.emplace_back(line.substr(0, tab), std::strtod(line.c_str() + tab + 1, nullptr));
  }
  return out;
}

void Store::fail(const char* what) {
  const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
  // SQLite's own words name no fix: say what the file is and what to do about it.
  if (msg.find("no such column") != std::string::npos || msg.find("no such table") != std::string::npos ||
      msg.find("has no column") != std::string::npos)
    throw Error(fmt::format("evaluation store '{}' has another layout ({}): it was written by another program or "
                            "another smi-lua version. Give a store written by this smi-lua, or move the file away "
                            "(with its -wal and -shm files) and a new store is started",
                            path_, msg));
  if (msg.find("not a database") != std::string::npos)
    throw Error(fmt::format("evaluation store '{}' is not an SQLite database ({}); give the path of an "
                            "evaluations.sqlite that smi-lua wrote",
                            path_, msg));
  throw Error(fmt::format("evaluation store '{}': {}: {}", path_, what, msg));
}

void Store::exec(const char* sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw Error(fmt::format("evaluation store '{}': {}", path_, msg));
  }
}

namespace {

/// "file:<path>?immutable=1" with the path percent-encoded where a URI needs it.
std::string immutable_uri(const std::string& path) {
  std::string u = "file:";
  for (unsigned char c : path) {
    if (c == '%' || c == '?' || c == '#' || c < 0x20) u += fmt::format("%{:02X}", c);
    else u += static_cast<char>(c);
  }
  return u + "?immutable=1";
}

// The store is opened through its folder's descriptor, not by name. SQLite's unix VFS takes
// only names, and it resolves links in them itself (unixFullPathname follows each one), so
// the name handed to it is "/proc/self/fd/<folder fd>/<file>": the kernel reaches the folder
// through the descriptor (a swapped or planted link on the path to it changes nothing), and
// the -wal and -shm files SQLite makes by appending to that name land in the same folder. A
// VFS shim ("smi-fd", the default VFS with its own xFullPathname) keeps that name as it is
// instead of resolving it back to text. Where /proc is not mounted (a bare chroot) the checked
// path is used as before. The files themselves are checked first: the store, its -wal, -shm and
// -journal must not be links or have other names (SQLite opens the -wal and -shm following links).
constexpr const char* kFdVfs = "smi-fd";

int keep_name(sqlite3_vfs* vfs, const char* name, int n_out, char* out) {
  if (std::strncmp(name, "/proc/self/fd/", 14) != 0) {
    auto* base = static_cast<sqlite3_vfs*>(sqlite3_vfs_find(nullptr));
    return base->xFullPathname(vfs, name, n_out, out);
  }
  if (static_cast<int>(std::strlen(name)) >= n_out) return SQLITE_CANTOPEN;
  std::memcpy(out, name, std::strlen(name) + 1);
  return SQLITE_OK;
}

const char* fd_vfs() {
  static const bool registered = [] {
    static sqlite3_vfs shim;
    const sqlite3_vfs* base = sqlite3_vfs_find(nullptr);
    if (!base) return false;
    shim = *base;
    shim.zName = kFdVfs;
    shim.pNext = nullptr;
    shim.xFullPathname = keep_name;
    return sqlite3_vfs_register(&shim, 0) == SQLITE_OK;
  }();
  return registered ? kFdVfs : nullptr;
}

/// Refuses a link or a hard link at `leaf` (and its SQLite companions) in the folder `dir`.
void check_store_files(int dir, const std::string& folder, const std::string& leaf) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    const std::string name = leaf + suffix;
    struct stat st {};
    if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) continue;  // not there: SQLite makes it
    const std::string shown = (std::filesystem::path(folder) / name).string();
    if (S_ISLNK(st.st_mode))
      throw Error(fmt::format("evaluation store file '{}' is a symbolic link; smi-lua writes the store and its -wal "
                              "and -shm files only as files of their own (a link would send the study's records "
                              "elsewhere): remove it and run again",
                              shown));
    if (!S_ISREG(st.st_mode))
      throw Error(fmt::format("evaluation store file '{}' is not a regular file: remove it and run again", shown));
    if (st.st_nlink > 1)
      throw Error(fmt::format("evaluation store file '{}' has {} hard links, so writing it would change a file "
                              "elsewhere: remove it (or copy it to a file of its own) and run again",
                              shown, st.st_nlink));
  }
}

}  // namespace

void Store::check_key_version(bool writable) {
  // PRAGMA user_version holds the key scheme. Version 2 keys include the SHA-256 of the
  // program file; an older store's records were keyed on the program's name and a version the
  // script chose, so a forged record could be reused: such a store is refused, not migrated.
  sqlite3_stmt* s = nullptr;
  long version = 0, tables = 0;
  if (sqlite3_prepare_v2(db_, "SELECT (SELECT user_version FROM pragma_user_version), "
                              "(SELECT count(*) FROM sqlite_master WHERE name = 'evaluations')",
                         -1, &s, nullptr) != SQLITE_OK)
    fail("read the store's version");
  if (sqlite3_step(s) == SQLITE_ROW) {
    version = sqlite3_column_int64(s, 0);
    tables = sqlite3_column_int64(s, 1);
  }
  sqlite3_finalize(s);
  if (tables == 0 && writable) {
    exec(fmt::format("PRAGMA user_version = {}", kKeyVersion).c_str());
    return;
  }
  if (tables > 0 && version != kKeyVersion)
    throw Error(fmt::format(
        "evaluation store '{}' was written by {} smi-lua (key scheme {}, this one uses {}: keys now include the "
        "program's SHA-256, so records keyed on a program name and a script-chosen version are not reused); "
        "its records cannot be reused: move it aside or delete it and run again{}",
        path_, version < kKeyVersion ? "an older" : "a newer", version, kKeyVersion,
        writable ? "" : " (it was given as --store)"));
}

Store::Store(const std::string& path, bool read_only, bool immutable) : path_(path), read_only_(read_only) {
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw Error(fmt::format("evaluation store '{}' is a folder; a store is one SQLite file: give its path, e.g. "
                              "--store {}/evaluations.sqlite",
                              path, path == "/" ? "" : std::filesystem::path(path).lexically_normal().string()));
  }
  if (immutable && !read_only) throw Error("evaluation store: immutable implies read-only");
  const int flags = read_only ? (SQLITE_OPEN_READONLY | SQLITE_OPEN_NOFOLLOW)
                              : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOFOLLOW);
  std::string name = path;  // what SQLite is given
  const char* vfs = nullptr;
  {
    const std::filesystem::path p(path);
    const std::string folder = p.has_parent_path() ? p.parent_path().string() : ".";
    dir_fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir_fd_ < 0)
      throw Error(fmt::format("cannot open the folder of evaluation store '{}': {}", path, std::strerror(errno)));
    try {
      check_store_files(dir_fd_, folder, p.filename().string());
    } catch (...) {
      ::close(dir_fd_);
      throw;
    }
    if (::access("/proc/self/fd", X_OK) == 0 && (vfs = fd_vfs()) != nullptr)
      name = fmt::format("/proc/self/fd/{}/{}", dir_fd_, p.filename().string());
  }
  if (sqlite3_open_v2(name.c_str(), &db_, flags, vfs) != SQLITE_OK) {
    ::close(dir_fd_);
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw Error(fmt::format("cannot open evaluation store '{}'{}: {}", path, read_only ? " (read-only)" : "", msg));
  }
  // A constructor that throws runs no destructor: release what is open before rethrowing (a
  // reader polling a store that another process is still creating meets this).
  try {
    sqlite3_busy_timeout(db_, 10000);  // two studies writing one store wait for each other
    if (read_only) {
      // A store given as --store is read immutable: never written, nor a -wal or -shm made
      // beside it (a WAL database opened read-only still writes its -shm); it is read as a
      // snapshot, as a published cache is. Other readers (tests polling a live store) read it
      // read-only, and fall back to immutable in a folder they may not write.
      if (immutable || sqlite3_exec(db_, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr) != SQLITE_OK) {
        sqlite3_close(db_);
        db_ = nullptr;
        if (sqlite3_open_v2(immutable_uri(name).c_str(), &db_,
                            SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOFOLLOW, vfs) != SQLITE_OK)
          fail("cannot open read-only");
      }
      check_key_version(false);
    } else {
      if (sqlite3_exec(db_, "PRAGMA journal_mode=WAL", nullptr, nullptr, nullptr) != SQLITE_OK) fail("open");
      exec("PRAGMA synchronous=NORMAL");
      check_key_version(true);
      if (sqlite3_exec(db_, kSchema, nullptr, nullptr, nullptr) != SQLITE_OK) fail("create the tables");
      if (sqlite3_prepare_v2(db_, kPut, -1, &put_, nullptr) != SQLITE_OK) fail("prepare insert");
    }
    if (sqlite3_prepare_v2(db_, kFind, -1, &find_, nullptr) != SQLITE_OK)
      fail(read_only ? "not an evaluation store (no 'evaluations' table)" : "prepare lookup");
  } catch (...) {  // plain C++ and SQLite only: no Lua here
    sqlite3_finalize(find_);
    sqlite3_finalize(put_);
    sqlite3_close(db_);
    ::close(dir_fd_);
    throw;
  }
}

Store::~Store() {
  sqlite3_finalize(find_);
  sqlite3_finalize(put_);
  sqlite3_close(db_);
  if (dir_fd_ >= 0) ::close(dir_fd_);
}

std::optional<Record> Store::find(const std::string& key) {
  Reset guard{find_};
  sqlite3_bind_text(find_, 1, key.c_str(), static_cast<int>(key.size()), SQLITE_TRANSIENT);
  const int rc = sqlite3_step(find_);
  if (rc == SQLITE_DONE) return std::nullopt;
  if (rc != SQLITE_ROW) fail("lookup");
  Record r;
  r.key = column_text(find_, 0);
  r.model = column_text(find_, 1);
  r.program = column_text(find_, 2);
  r.version = column_text(find_, 3);
  r.inputs = decode_values(column_text(find_, 4));
  r.outputs = decode_values(column_text(find_, 5));
  r.ok = column_text(find_, 6) == "ok";
  r.reason = column_text(find_, 7);
  r.duration = sqlite3_column_double(find_, 8);
  r.attempts = sqlite3_column_int(find_, 9);
  r.stdout_tail = column_text(find_, 10);
  r.stderr_tail = column_text(find_, 11);
  r.workdir = column_text(find_, 12);
  return r;
}

void Store::put(const Record& r) {
  if (read_only_) throw Error(fmt::format("evaluation store '{}' is read-only", path_));
  Reset guard{put_};
  const std::string inputs = encode_values(r.inputs), outputs = encode_values(r.outputs);
  auto text = [&](int i, const std::string& s) {
    sqlite3_bind_text(put_, i, s.c_str(), static_cast<int>(s.size()), SQLITE_TRANSIENT);
  };
  text(1, r.key);
  text(2, r.model);
  text(3, r.program);
  text(4, r.version);
  text(5, inputs);
  text(6, outputs);
  text(7, r.ok ? std::string("ok") : std::string("failed"));
  text(8, r.reason);
  sqlite3_bind_double(put_, 9, r.duration);
  sqlite3_bind_int(put_, 10, r.attempts);
  text(11, r.stdout_tail);
  text(12, r.stderr_tail);
  text(13, r.workdir);
  if (sqlite3_step(put_) != SQLITE_DONE) fail("write");
}

Timing Store::timing(const std::string& program, const std::string& version) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT count(*), avg(duration) FROM evaluations WHERE program = ?1 AND version = ?2 "
                              "AND status = 'ok'", -1, &s, nullptr) != SQLITE_OK)
    fail("prepare timing");
  sqlite3_bind_text(s, 1, program.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, version.c_str(), -1, SQLITE_TRANSIENT);
  Timing t;
  if (sqlite3_step(s) == SQLITE_ROW) {
    t.count = sqlite3_column_int64(s, 0);
    t.mean = sqlite3_column_double(s, 1);
  }
  sqlite3_finalize(s);
  return t;
}

long Store::count() {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT count(*) FROM evaluations", -1, &s, nullptr) != SQLITE_OK) fail("prepare count");
  long n = 0;
  if (sqlite3_step(s) == SQLITE_ROW) n = static_cast<long>(sqlite3_column_int64(s, 0));
  sqlite3_finalize(s);
  return n;
}

}  // namespace smi::eval
