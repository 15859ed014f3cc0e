// SPDX-License-Identifier: MIT
#pragma once
// The store's pending table: solver runs handed to a scheduler that outlives smi-lua (Slurm),
// key -> job, so that a rerun after a crash, kill -9 or --detach reattaches to jobs still queued
// or running, or reads the exit files of those that finished meanwhile, and submits none twice.
// It lives in the evaluation store's database (one SQLite file on the submitting host; compute
// nodes never open it) and only the evaluator's process writes it.
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace smi::eval {

struct PendingRun {
  std::string key;         // the run's store key
  std::string job_name;    // the chunk's unique job name (written before sbatch)
  std::string job_id;      // the array job id ("" until sbatch answered)
  int array_index = 0;     // the task index in that array
  int attempt = 1;         // the evaluator's attempt number
  std::string workdir;     // the run's folder (its .smi/exit file decides the outcome)
};

class PendingTable {
 public:
  /// Creates the table in `db` if missing. `db` must stay open while this object lives.
  explicit PendingTable(sqlite3* db);
  std::optional<PendingRun> find(const std::string& key);
  /// Inserts or replaces all rows in one transaction.
  void put(const std::vector<PendingRun>& rows);
  /// Sets job_id for every row of `job_name` (after sbatch answered).
  void set_job_id(const std::string& job_name, const std::string& job_id);
  /// Removes the row of `key` if it still belongs to `job_id` (a retry may have replaced it).
  void erase(const std::string& key, const std::string& job_id);
  long count();

 private:
  void exec(const std::string& sql);
  sqlite3* db_;
};

}  // namespace smi::eval
