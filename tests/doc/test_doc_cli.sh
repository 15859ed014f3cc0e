#!/bin/bash
# SPDX-License-Identifier: MIT
# smi-lua doc on the command line: the same texts as help(), defaults from the kernels' option
# structs, search, the module list; the coverage check fails on a public function without a
# text and on an example that fails; a study's declared options (--help, a wrong value).
source "$SMI_SOURCE_DIR/tests/cli/lib.sh"

run "doc NAME" 0 "$SMI" doc smi.kde
has_out 'smi.kde(data [, opts]) -> dist'
has_out 'bandwidth = "silverman"'
has_out 'tol = 1e-06'            # KdeOptions::binned_tol
has_out 'example:'
run "doc NAME: defaults from BoundedKdeOptions" 0 "$SMI" doc smi.kde_bd
has_out 'critical_area = 0.95'
has_out 'max_added = -1'
has_out 'grid_nodes = 4001'
run "doc METHOD" 0 "$SMI" doc smi.kriging:predict
has_out 'smi.kriging:predict(X [, opts]) -> mean, mse'
run "doc WORD searches" 0 "$SMI" doc bandwidth
has_out "entries mention 'bandwidth'"
has_out 'smi.kde_ebd'
# A name that matches nothing: the closest names, status 2 (smi.kdee once said nothing, status 0)
run "doc misspelt NAME" 2 "$SMI" doc smi.kdee
has_err "did you mean smi.kde"
run "doc words in any order" 0 "$SMI" doc prior weight
has_out 'smi.calibrate'
run "doc alone lists the modules" 0 "$SMI" doc
has_out 'smi.calibrate'
has_out 'smi.report'
has_out 'smi.options'
run "doc: unknown option" 2 "$SMI" doc --bogus
has_err "unknown option '--bogus'"
run "doc --missing: complete" 0 "$SMI" doc --missing
has_out '0 without a complete doc text, 0 stale texts'

# A public function without a text, and a stale text, fail the coverage check.
cp -r "$SMI_SOURCE_DIR/stdlib" "$WORK/stdlib"
sed -i 's/^return M$/function M.undocumented() end\nreturn M/' "$WORK/stdlib/smi/testing.lua"
run "doc --missing: a function without a text" 1 "$SMI" doc --missing --stdlib-dir "$WORK/stdlib"
has_err 'no doc text: smi.testing.undocumented'
cp "$SMI_SOURCE_DIR/stdlib/smi/testing.lua" "$WORK/stdlib/smi/testing.lua"
sed -i 's/^@ smi.testing.rel(actual, expected, rtol \[, what\])$/@ smi.testing.relative(actual, expected, rtol [, what])/' "$WORK/stdlib/smi/testing.lua"
run "doc --missing: a text whose function is gone" 1 "$SMI" doc --missing --stdlib-dir "$WORK/stdlib"
has_err 'no doc text: smi.testing.rel'
has_err 'doc text for a name that does not exist: smi.testing.relative'
# An example that fails fails the check, naming the entry.
cp "$SMI_SOURCE_DIR/stdlib/smi/testing.lua" "$WORK/stdlib/smi/testing.lua"
sed -i 's/T.near(math.pi, 3.14159, 1e-5, "pi")/T.near(math.pi, 3.14159, 1e-9, "pi")/' "$WORK/stdlib/smi/testing.lua"
run "doc --check: a failing example" 1 "$SMI" doc --check --stdlib-dir "$WORK/stdlib" --out "$WORK/out"
has_err 'example of smi.testing.near failed'
has_out '1 failed'

# A study's declared options (smi.options in scripts/steering_column.lua).
SC="$SMI_SOURCE_DIR/scripts/steering_column.lua"
run "study --help" 0 "$SMI" "$SC" --help
has_out '--metric=pr|loglik'
has_out '[default: pr]'
has_out '--multistart=N'
has_out '--only=A[,B...]'
run "study: a wrong value names the option and the allowed values" 2 "$SMI" "$SC" --metric rmse
has_err "$SC: --metric: 'rmse' is not allowed; allowed values: pr, loglik"  # the script as it was run
run "study: a number below its minimum" 2 "$SMI" "$SC" --multistart 0
has_err '--multistart: 0 is below the minimum 1'
run "study: an unknown option" 2 "$SMI" "$SC" --metirc pr
has_err "unknown option '--metirc' (did you mean --metric?)"

finish
