// SPDX-License-Identifier: MIT
#pragma once
// Caps that options set by a script cannot pass: what the machine can actually do at once.
// A script asking for 100,000 threads or 200 concurrent solver processes gets the machine's
// count instead of aborting the process or thrashing it.
namespace smi::machine {

/// Hardware threads of this machine (at least 1).
int cores();
/// `requested` clamped to [1, cores()].
int cap_threads(long long requested);

}  // namespace smi::machine
