// SPDX-License-Identifier: MIT
#pragma once
// One study per output folder at a time. Two smi-lua processes writing one --out would share
// work folders (one clears the other's run), results.json and report.html. The first to
// start a study or a solver model there takes an exclusive flock on <folder>/.smi-lock and
// writes who it is (pid, host, start time, command); it holds the lock until it exits (the
// kernel drops it even after kill -9, so a stale file never blocks). A second process gets an
// error naming the holder and the fix.
#include <string>

namespace smi::eval {

/// Locks `folder` (created if missing) for the rest of this process; a no-op if this process
/// holds it already. Throws smi::Error naming the holder when another process does.
void lock_output_folder(const std::string& folder);

}  // namespace smi::eval
