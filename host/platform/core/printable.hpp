// SPDX-License-Identifier: MIT
#pragma once
// Text from data (a results file, a solver's log, an error message carrying either) made safe
// for a terminal: control characters become visible escapes, so data cannot move the cursor,
// rewrite a line already printed ("everything matches") or change the terminal's state.
#include <string>
#include <string_view>

namespace smi {

/// `s` with C0 controls (but newline and tab), DEL and the C1 controls (U+0080-U+009F, as
/// UTF-8 or as single bytes) written as \xHH (the C1 ones as \u{HH}); other bytes unchanged.
std::string printable(std::string_view s);

}  // namespace smi
