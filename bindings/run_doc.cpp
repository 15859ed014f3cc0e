// SPDX-License-Identifier: MIT
// Reference texts of the run-level functions (registered in run.cpp; format: stdlib/smi/doc.lua).
#include "bindings/doc.hpp"

namespace smi::bind {

// long: one raw string of reference text (data, no logic); doc.lua reads it entry by entry
DocText doc_run() {
  return {"bindings/run_doc.cpp", R"DOC(
@ smi.out([name]) -> path
A path in the run's output folder (--out, default smi-out/<script>/), which is created on
first use. Scripts write their files here: the sandbox allows writes under it.
returns: the path as a string (the folder itself when name is omitted)
errors: the folder cannot be created (a file is in the way, or no permission)
example:
  local p = smi.out("table.csv")
  print(p:match("table%.csv$") ~= nil)

@ smi.now() -> seconds
Wall-clock seconds from a monotonic clock, for timing steps that wait on solver processes
(os.clock counts only this process's CPU time).
returns: a number of seconds from an arbitrary origin; differences are durations
errors: none
example:
  local t0 = smi.now()
  print(smi.now() - t0 >= 0)

@ smi.write_file(path, text) -> path
Writes a whole file atomically: a temporary file in the same folder (created O_EXCL, never
through a symlink), every write checked, fsync, then renamed over the target. A full disk or a
kill leaves the old file as it was. smi.study writes results.json and report.html this way.
returns: the path as given
errors: the sandbox refuses the folder (write only under --out and --allow-write); the target is
  a symlink; a write fails (the message names the file and the reason, e.g. no space left)
example:
  local p = smi.write_file(smi.out("note.txt"), "done\n")
  print(p:match("note%.txt$") ~= nil)

@ smi.lock_out([folder]) -> nothing
Takes this process's lock on an output folder (default --out), so that two studies never share
work folders or results; smi.study calls it before its first step. The lock is released when the
process ends.
returns: nothing
errors: another process holds the lock (the message names its pid, host, start time and command,
  and the fix: wait for it or give another --out); the sandbox refuses the folder
example:
  smi.lock_out()
  print("locked")

@ smi.warnings() -> list
The run's warnings so far, in order, each as "<function>: <text>" (data outside a KDE's bounds,
duplicated CSV rows, an integration grid too coarse for a pdf, ...). Every warning a smi function
gives comes here; it is also printed on stderr as "<function>: warning: <text>" unless the run is
quiet (--quiet, or output not a terminal), so a quiet run loses none.
returns: a list of strings (empty when nothing was warned)
errors: none
example:
  for _, w in ipairs(smi.warnings()) do print(w) end
  print(#smi.warnings() >= 0)

@ smi.fail(message [, traceback]) -> never returns
Raises a failure: an error in the user's data, options or declaration (a missing column, a bad
option value, an unknown distribution family), as opposed to an error in code. smi-lua prints a
failure as one line, "smi-lua: <message>", with no Lua traceback (--traceback adds it); an error
in code keeps its traceback. The message names the culprit (file, line, field, value) and the
fix. The error value is a table whose tostring is the message; string methods (e:find, e:match)
and `..` act on the message, and smi.failure(e) returns it. Every check of smi's own raises one,
and so does a smi function called by the stdlib. With a traceback (a step of smi.study catching an
error in the user's code), the failure carries that traceback, which is printed under it.
returns: never (raises)
errors: always: the failure
example:
  local msg = "tests.csv: no column 'mode2_Hz' (did you mean mode_2_Hz?); columns: mode_1_Hz, mode_2_Hz"
  local ok, e = pcall(smi.fail, msg)
  print(ok, smi.failure(e), e:find('mode2') ~= nil)

@ smi.failure(e) -> message | nil
The message of a failure raised by smi.fail (or by a smi check), nil for any other error value:
tells an error in the user's data or declaration from an error in code after a pcall.
returns: a string, or nil
errors: none
example:
  local _, e = pcall(smi.fail, 'bad value')
  local _, plain = pcall(error, 'plain error')
  print(smi.failure(e), smi.failure(plain))

@ smi.progress_label([text]) -> nothing
What the progress lines that follow belong to, written in front of each ("[beam] step 4/7
calibrate: calibration: start 2/4, 310 evaluations"); no text clears it. smi.study sets it to
the step that runs.
returns: nothing
errors: none
example:
  smi.progress_label('[demo] fit')
  smi.progress_label()
  print("ok")
)DOC"};
}

}  // namespace smi::bind
