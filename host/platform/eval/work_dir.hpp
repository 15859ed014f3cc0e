// SPDX-License-Identifier: MIT
#pragma once
// One folder per solver run: created fresh (a leftover from a killed or failed attempt is
// removed first), holding the rendered deck, copies of the model's extra files, and the
// captured stdout/stderr.
#include <memory>
#include <string>
#include <vector>

#include "platform/core/path_walk.hpp"

namespace smi::eval {

inline constexpr const char* kStdoutFile = "stdout.log";
inline constexpr const char* kStderrFile = "stderr.log";

/// Removes `dir` if it exists, creates it (and its parents), writes `deck_text` to
/// dir/deck_name and copies each of `files` into it under its own file name. Throws smi::Error
/// naming the path on any filesystem failure.
/// `fds` (same order as `files`, may be shorter) are the checked descriptors to copy from.
/// Nothing is followed through a symlink: the folder's path is opened with O_NOFOLLOW at each
/// component and files are created with O_EXCL | O_NOFOLLOW.
void prepare_work_dir(const std::string& dir, const std::string& deck_name, const std::string& deck_text,
                      const std::vector<std::string>& files,
                      const std::vector<std::shared_ptr<const pathwalk::Fd>>& fds = {});

/// Writes a whole file (binary), throwing smi::Error naming it on failure.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace smi::eval
