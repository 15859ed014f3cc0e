// SPDX-License-Identifier: MIT
#pragma once
// Writing a file so that readers see the old content or the new, never a torn or shortened
// mix: the text goes to a temporary file beside the target, every write is checked, the data
// are flushed to disk (fsync) and the temporary file is renamed over the target (atomic on
// POSIX), then the folder is synced so the rename itself survives a crash. On any failure
// (disk full, quota, I/O error) the temporary file is removed, the target is left as it was,
// and smi::Error names the file and the system's reason.
#include <string>
#include <string_view>

namespace smi {

/// `mode` is the new file's permission bits (before the umask), e.g. 0755 for a job script.
void write_file_atomic(const std::string& path, std::string_view data, unsigned mode = 0644);

}  // namespace smi
