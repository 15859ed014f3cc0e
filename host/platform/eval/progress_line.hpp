// SPDX-License-Identifier: MIT
#pragma once
// The one-line progress display of a running evaluation, and the dry-run summary. Formatting
// lives here (testable); the binding decides whether to show it (stderr is a terminal and the
// study is not --quiet).
#include <cstdio>
#include <string>

#include "platform/eval/evaluator.hpp"

namespace smi::eval {

/// "1:02:03", "4:05", "12 s", "0.35 s"; "?" for a negative (unknown) duration.
std::string format_duration(double seconds);

/// "column: 12/40 runs done, 1 failed, 2 running, mean 1.3 s, ETA 0:40"
std::string format_progress(const std::string& model, const Progress& p);

/// "dry run: model 'column' would launch 28 solver runs for 40 points (12 found in the store);
///  ETA 6:20 at concurrency 2 from 31 stored runs (mean 27 s)"
std::string format_plan(const std::string& model, const Plan& p, int concurrency);

/// Rewrites the current terminal line with `text` (carriage return, clear to end of line);
/// `final` ends it with a newline.
void show_progress(std::FILE* tty, const std::string& text, bool final);

}  // namespace smi::eval
