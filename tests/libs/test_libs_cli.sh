# SPDX-License-Identifier: MIT
# Library sharing end to end, on real library folders made as git repositories: new-lib + test,
# libs, a version conflict, a missing requirement, require "name.module", provenance in the
# results file and verify catching a tampered library, and a library held to the sandbox.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir

gitc() { git -C "$1" -c user.name=t -c user.email=t@example.org -c init.defaultBranch=main "${@:2}" > /dev/null 2>&1; }
# make_lib DIR NAME VERSION REQUIRES_LUA : a library checked into its own git repository
make_lib() {
  mkdir -p "$1"
  printf 'name = "%s"\nversion = "%s"\ndescription = "test library"\nrequires = {%s}\n' "$2" "$3" "$4" > "$1/smi-lib.lua"
  printf 'return { version = "%s" }\n' "$3" > "$1/init.lua"
  gitc "$1" init -q && gitc "$1" add -A && gitc "$1" commit -q -m "release $3"
}

# --- new-lib + test round trip --------------------------------------------------------------
run new-lib 0 "$SMI" new-lib kdetools
has_out "created library 'kdetools'"
run new-lib-exists 1 "$SMI" new-lib kdetools
has_err "already exists"
run new-lib-bad-name 2 "$SMI" new-lib 9lives
has_err "not a valid library name"
run test-roundtrip 0 "$SMI" test kdetools
has_out "ok    tests/test_kdetools.lua (2 passed, 0 failed)"
# the summary counts cases, as each file does
has_out "2 passed, 0 failed (1 test file, 0 failed)"
# a wrong expectation makes the test file fail, and the count says so
sed -i 's|9 / 4|9 / 5|' kdetools/tests/test_kdetools.lua
run test-failing 1 "$SMI" test kdetools
has_out "FAIL  tests/test_kdetools.lua"
has_out "1 passed, 1 failed (1 test file, 1 failed)"
has_out "expected 1.8"
run test-not-a-lib 1 "$SMI" test .
has_err "has no smi-lib.lua"

# --- libs lists name, version, commit, path -----------------------------------------------
make_lib team/kdetools kdetools 1.3.0 ""
make_lib team/refcrit refcrit 2.1.0 '"kdetools >= 1.2, < 2"'
mkdir -p team/refcrit/criteria && printf 'return { area = function(a, b) return math.abs(a - b) end }\n' > team/refcrit/criteria/area.lua
printf 'return { weight = 0.25 }\n' > team/refcrit/weights.lua
gitc team/refcrit add -A && gitc team/refcrit commit -q -m criteria
k_commit=$(git -C team/kdetools rev-parse HEAD)
r_commit=$(git -C team/refcrit rev-parse HEAD)
run libs 0 "$SMI" libs --lib team
has_out "kdetools  1.3.0    ${k_commit:0:12}  $WORK/team/kdetools"
has_out "refcrit   2.1.0    ${r_commit:0:12}  $WORK/team/refcrit"
run libs-empty 0 "$SMI" -E libs
has_out "no libraries on the library path"

# --- require "name.module" -----------------------------------------------------------------
mkdir -p study
cat > study/uses.lua <<'LUA'
print("STARTED")
local r = require "refcrit"
local area = require "refcrit.criteria.area"
print(r.version, require("refcrit.weights").weight, area.area(3, 1), require("kdetools").version)
LUA
run require 0 "$SMI" --lib team study/uses.lua
has_out "2.1.0	0.25	2	1.3.0"
# smi.libraries(): what the study sees, and which it used
printf 'require "refcrit"\nfor _, l in ipairs(smi.libraries()) do print(l.name, l.version, l.used, l.commit, l.requires[1]) end\n' > study/list.lua
run libraries-lua 0 "$SMI" --lib team study/list.lua
has_out "kdetools	1.3.0	false	$k_commit	nil"
has_out "refcrit	2.1.0	true	$r_commit	kdetools >= 1.2, < 2"
run require-missing-module 1 "$SMI" --lib team -e 'require "refcrit.nothere"'
has_err "no file '$WORK/team/refcrit/nothere.lua'"
has_err "(library refcrit 2.1.0)"

# --- a version conflict stops the study before it starts ----------------------------------
make_lib old/kdetools kdetools 1.0.0 ""
SMI_PATH=old run conflict 1 "$SMI" --lib team study/uses.lua
has_err "two copies of library 'kdetools'"
has_err "kdetools 1.3.0 at $WORK/team/kdetools (--lib team)"
has_err "kdetools 1.0.0 at $WORK/old/kdetools (SMI_PATH old)"
has_err "remove one of the two folders"
lacks_out "STARTED"
SMI_PATH=old run conflict-libs 1 "$SMI" libs --lib team
has_err "two copies of library 'kdetools'"

# --- a missing or too old requirement -------------------------------------------------------
run missing-req 1 "$SMI" --lib team/refcrit study/uses.lua
has_err "library refcrit 2.1.0 ($WORK/team/refcrit/smi-lib.lua) requires 'kdetools >= 1.2, < 2', but no library 'kdetools' is on the library path"
has_err "add the folder holding it with --lib DIR"
lacks_out "STARTED"
run old-req 1 "$SMI" --lib team/refcrit --lib old study/uses.lua
has_err "but kdetools 1.0.0 at $WORK/old/kdetools (--lib old) does not satisfy >= 1.2, < 2"

# --- a manifest is data: code in it is refused ----------------------------------------------
mkdir -p bad/evilman && printf 'name = "evilman"\nversion = "1.0.0"\nos.execute("touch pwned")\n' > bad/evilman/smi-lib.lua
run manifest-code 1 "$SMI" --lib bad -e 'print(1)'
has_err "library manifest '$WORK/bad/evilman/smi-lib.lua' failed"
if [ -e pwned ]; then bad "the manifest ran os.execute"; else ok; fi

# --- provenance in the results file, and verify -----------------------------------------------
cat > study/study.lua <<'LUA'
local study = require "smi.study"
local s = study.new{name = "demo", out = smi.out_dir}
-- non-finite results (a diverged metric) are kept by the results-file rule and must not stop verify
s:step("score", function() return {area = require("refcrit.criteria.area").area(5, 2), worst = math.huge,
                                   best = -math.huge, ratio = 0 / 0} end)
s:run()
LUA
run study 0 "$SMI" --quiet --lib team --seed 7 --out out study/study.lua
results=out/results.json
if grep -q '"provenance"' $results && grep -q "\"commit\": *\"$r_commit\"" $results && grep -q '"seed": *7' $results \
   && grep -q '"smi_lua"' $results && grep -q '"criteria/area.lua"' $results; then ok; else bad "provenance missing from $results: $(head -c 800 $results)"; fi
if grep -q '"worst": 1e999' $results && grep -q '"best": -1e999' $results && grep -q '"ratio": null' $results; then ok
else bad "non-finite results not kept as 1e999/-1e999/null in $results"; fi
run verify-same 0 "$SMI" verify --lib team $results
has_out "ok       refcrit 2.1.0"
has_out "ok       kdetools 1.3.0"
has_out "everything matches; rerun with --seed 7"
# without --lib, verify looks at the recorded folders
run verify-recorded 0 "$SMI" verify $results
has_out "refcrit 2.1.0 at its recorded path"
# tamper: one changed file, one added file
printf 'return { area = function(a, b) return 2 * math.abs(a - b) end }\n' > team/refcrit/criteria/area.lua
printf 'return {}\n' > team/refcrit/extra.lua
run verify-tampered 1 "$SMI" verify --lib team $results
has_out "CHANGED  refcrit 2.1.0"
has_out "changed: criteria/area.lua"
has_out "added:   extra.lua"
has_out "ok       kdetools 1.3.0"
lacks_out "changed: weights.lua"
has_out "1 library changed"
# committing the change does not hide it: the commit differs and so does the content
gitc team/refcrit add -A && gitc team/refcrit commit -q -m tweak
run verify-committed 1 "$SMI" verify --lib team $results
has_out "recorded commit ${r_commit:0:12}, now commit $(git -C team/refcrit rev-parse HEAD | cut -c1-12)"
# restoring the files restores the match
gitc team/refcrit checkout -q "$r_commit"
run verify-restored 0 "$SMI" verify --lib team $results
mv team/kdetools kdetools.gone
run verify-missing 1 "$SMI" verify --lib team $results
has_out "MISSING  kdetools 1.3.0"
mv kdetools.gone team/kdetools
run verify-no-provenance 2 "$SMI" verify study/uses.lua   # not a results file: exit 2
has_err "not valid JSON"
# the recorded seed is the integer itself, also above 2^53 (a double rounded it to another seed)
# and above 2^63 (smi.seed is a Lua integer: the results file holds it negative)
printf '{"provenance": {"seed": 9007199254740993, "libraries": []}}\n' > big_seed.json
run verify-big-seed 0 "$SMI" verify big_seed.json
has_out "rerun with --seed 9007199254740993 "
printf '{"provenance": {"seed": -1, "libraries": []}}\n' > top_seed.json
run verify-top-seed 0 "$SMI" verify top_seed.json
has_out "rerun with --seed 18446744073709551615 "

# --- a library runs in the study's sandbox --------------------------------------------------
echo "s3cret" > secret.txt
make_lib team/snoop snoop 0.1.0 ""
cat > team/snoop/init.lua <<'LUA'
local M = {}
function M.read(p) local f = assert(io.open(p)) local s = f:read("a") f:close() return s end
function M.write(p) local f = assert(io.open(p, "w")) f:write("x") f:close() end
return M
LUA
# the study lives in study/; secret.txt beside it is outside what the study may read
printf 'print(require("snoop").read(...))\n' > study/read.lua
printf 'require("snoop").write(...)\n' > study/write.lua
run snoop-read 1 "$SMI" --lib team study/read.lua secret.txt
has_err "reading 'secret.txt' (resolved to '$WORK/secret.txt') is not allowed"
has_err "$WORK/team/snoop/init.lua:2:"
lacks_out "s3cret"
run snoop-climb 1 "$SMI" --lib team study/read.lua team/snoop/../../secret.txt
has_err "(resolved to '$WORK/secret.txt') is not allowed"
run snoop-etc 1 "$SMI" --lib team study/read.lua /etc/passwd
has_err "reading '/etc/passwd'"
run snoop-write 1 "$SMI" --lib team study/write.lua team/refcrit/init.lua
has_err "writing 'team/refcrit/init.lua'"
# symlink out of the library folder: require refuses it like io.open
ln -s "$WORK/secret.txt" team/snoop/leak.lua
printf 'require "snoop.leak"\n' > study/leak.lua
run snoop-symlink 1 "$SMI" --lib team study/leak.lua
has_err "reading '$WORK/team/snoop/leak.lua' (a link on the way leads outside the folders allowed) is not allowed"
rm team/snoop/leak.lua
# what the study's user allows, the library may do; its own folder it may always read
run snoop-allowed 0 "$SMI" --lib team --allow-read secret.txt study/read.lua secret.txt
has_out "s3cret"
run snoop-own 0 "$SMI" --lib team study/read.lua team/snoop/smi-lib.lua
has_out 'name = "snoop"'

finish
