# SPDX-License-Identifier: MIT
# A library's name and version are data, never paths; a library is exactly its files; git runs
# with a protocol allow-list and a time limit. Each case is an attempt to make smi-lua install,
# remove or read outside the project's library tree, or to run a study on changed library code:
# versions whose build metadata or prerelease holds a path, names with separators, lockfiles
# forged with valid checksums (tests/libs/lockfile_forge.py), smi-libs and name folders that are
# symbolic links, a lockfile tree outside the project, remote-helper sources, a git that never
# answers, and files added under smi-out/ after locking.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir
FORGE="/usr/bin/python3 ${SMI_SOURCE_DIR}/tests/libs/lockfile_forge.py"

lib() {  # lib DIR NAME VERSION [REQUIRES_LUA] [SOURCES_LUA]: a library folder
  mkdir -p "$1"
  printf 'name = "%s"\nversion = "%s"\nrequires = {%s}\nsources = {%s}\n' "$2" "$3" "${4:-}" "${5:-}" > "$1/smi-lib.lua"
  printf 'return { version = "%s" }\n' "$3" > "$1/init.lua"
}
nothing_escaped() {  # no file or folder was made outside the project folders
  if [ -z "$(find "$WORK" -maxdepth 3 -name 'escaped*' 2>/dev/null)" ]; then ok; else bad "escaped: $(find "$WORK" -name 'escaped*')"; fi
}

# --- versions and names that are paths, at every entry: a folder, a dependency, an archive -------
mkdir -p p && cd p
for v in '1.0.0+x/../../../../escaped' '1.0.0+x/../../escaped1' '1.0.0+../escaped2' '1.0.0-a/../../escaped3' \
         '1.0.0+' '1.0.0+a..b' '1.0.0+a\\b' '1.0.0+/abs'; do
  lib "../evil" evil "$v"
  run "version-$v" 1 "$SMI" libs add ../evil
  has_err "version '"
  nothing_escaped
done
if [ ! -e smi-lock.json ] && [ -z "$(find smi-libs -mindepth 1 2>/dev/null)" ]; then ok; else bad "a refused add left files: $(find . | head)"; fi
for n in 'a/b' '..' 'a\\b' '/abs' 'a.b' 'x\0y'; do
  lib "../evilname" "$n" 1.0.0
  run "name-$n" 1 "$SMI" libs add ../evilname
  has_err "is not a valid library name"
done
# a dependency through `sources` whose manifest has a path for a version
lib ../dep dep '1.0.0+x/../../../../escaped'
lib ../good good 1.0.0 '"dep"' 'dep = "../dep"'
run dependency-version 1 "$SMI" libs add ../good
has_err "build metadata identifiers use only [0-9A-Za-z-]"
nothing_escaped
# an archive made by libs pack from such a folder is refused when packed and when added
lib ../dep dep '1.0.0+x/../../escaped'
run pack-version 1 "$SMI" libs pack ../dep
has_err "build metadata"
cd ..

# --- forged lockfiles (valid checksums): version, name and tree as paths ---------------------------
mkdir -p victim/keep && echo precious > victim/keep/data.txt
mkdir -p f1 && cd f1
lib ../okl okl 1.0.0
"$SMI" libs add ../okl > /dev/null 2>&1 || bad "setup: libs add ../okl"
cp smi-lock.json ../lock.ok
/usr/bin/python3 - <<'PY'
import json
d = json.load(open("smi-lock.json"))
d["libraries"][0]["version"] = "1.0.0+x/../../../victim/keep"
json.dump(d, open("smi-lock.json", "w"))
PY
$FORGE smi-lock.json
run forged-version-sync 1 "$SMI" libs sync
has_err "build metadata identifiers"
run forged-version-remove 1 "$SMI" libs remove okl
run forged-version-study 1 "$SMI" -e 'print(1)'
if [ -f ../victim/keep/data.txt ]; then ok; else bad "a forged version removed a folder outside the project"; fi
# a forged name
cp ../lock.ok smi-lock.json
/usr/bin/python3 - <<'PY'
import json
d = json.load(open("smi-lock.json"))
d["libraries"][0]["name"] = "../../victim"
json.dump(d, open("smi-lock.json", "w"))
PY
$FORGE smi-lock.json
run forged-name-remove 1 "$SMI" libs remove ../../victim
has_err "not a valid library name"
# a forged tree: absolute, and relative with '..'
for t in "$WORK/victim" "../victim"; do
  cp ../lock.ok smi-lock.json
  mkdir -p ../victim/okl/1.0.0 && cp ../okl/* ../victim/okl/1.0.0/ && echo precious > ../victim/okl/1.0.0/data.txt
  T="$t" /usr/bin/python3 - <<'PY'
import json, os
d = json.load(open("smi-lock.json"))
d["tree"] = os.environ["T"]
json.dump(d, open("smi-lock.json", "w"))
PY
  $FORGE smi-lock.json
  run "forged-tree-remove $t" 1 "$SMI" libs remove okl
  has_err "outside the project folder"
  has_err "--into"
  if [ -f ../victim/okl/1.0.0/data.txt ]; then ok; else bad "libs remove deleted a folder the forged tree '$t' named"; fi
  run "forged-tree-sync $t" 1 "$SMI" libs sync
  # the tree is no read root of a study: the study does not start, and says how to allow it
  run "forged-tree-read $t" 1 "$SMI" -e "print(io.open('$WORK/victim/keep/data.txt'):read('a'))"
  has_err "outside the project folder; a study reads a tree outside its folder only when you give it yourself: --lib"
  lacks_out precious
done
cd ..

# --- smi-libs and its name folders as symbolic links --------------------------------------------------
mkdir -p secret && echo topsecret > secret/s.txt
mkdir -p b1 && cd b1
ln -s ../secret smi-libs
run smi-libs-link-study 1 "$SMI" -e "print(io.open('$WORK/secret/s.txt'):read('a'))"
has_err "is a symbolic link"
lacks_out topsecret
run smi-libs-link-add 1 "$SMI" libs add ../okl
has_err "is a symbolic link"
if [ ! -e ../secret/okl ]; then ok; else bad "libs add installed through the smi-libs link"; fi
cd .. && mkdir -p b2 && cd b2
"$SMI" libs add ../okl > /dev/null 2>&1 || bad "setup: libs add ../okl in b2"
rm -rf smi-libs && ln -s ../secret smi-libs
run locked-tree-link-study 1 "$SMI" -e "print(io.open('$WORK/secret/s.txt'):read('a'))"
has_err "is a symbolic link"
lacks_out topsecret
run locked-tree-link-sync 1 "$SMI" libs sync
has_err "is a symbolic link"
rm smi-libs && mkdir -p smi-libs victim2/1.0.0 && echo precious > victim2/1.0.0/data.txt
ln -s ../victim2 smi-libs/okl
run name-folder-link-remove 1 "$SMI" libs remove okl
has_err "is a symbolic link or not a folder"
if [ -f victim2/1.0.0/data.txt ]; then ok; else bad "libs remove followed a linked name folder"; fi
run name-folder-link-sync 1 "$SMI" libs sync
has_err "is a symbolic link or not a folder"
cd ..

# --- a library is exactly its files: smi-out/ counts, and a study stops on a changed library ------
mkdir -p h && cd h
lib ../hl hl 1.0.0
"$SMI" libs add ../hl > /dev/null 2>&1 || bad "setup: libs add ../hl"
cat > study.lua <<'LUA'
print("VERSION", require("hl").version)
LUA
run clean-study 0 "$SMI" study.lua
has_out "VERSION	1.0.0"
mkdir -p smi-libs/hl/1.0.0/smi-out && echo 'return "pwned"' > smi-libs/hl/1.0.0/smi-out/payload.lua
run smi-out-check 1 "$SMI" libs sync --check
has_err "file 'smi-out/payload.lua' is not in smi-lock.json"
run smi-out-study 1 "$SMI" study.lua
has_err "library hl 1.0.0 at"
has_err "file 'smi-out/payload.lua' is not in smi-lock.json"
has_err "restore it with: smi-lua libs sync"
lacks_out VERSION
echo 'return { version = "6.6.6" }' > smi-libs/hl/1.0.0/init.lua
run changed-study 1 "$SMI" study.lua
has_err "file 'init.lua' differs from smi-lock.json"
run repair 0 "$SMI" libs sync
has_out "restored   hl 1.0.0"
if [ ! -e smi-libs/hl/1.0.0/smi-out ] && cmp -s smi-libs/hl/1.0.0/init.lua ../hl/init.lua; then ok; else bad "sync did not repair"; fi
run repaired-study 0 "$SMI" study.lua
has_out "VERSION	1.0.0"
cd ..

# --- git: no remote helpers, file/https/ssh only, a time limit ---------------------------------------
mkdir -p g && cd g
lib ../needsfd needsfd 1.0.0 '"dep"' 'dep = "fd::7"'
SECONDS=0
run fd-helper-dependency 1 timeout 30 "$SMI" libs add ../needsfd
has_err "names the git remote helper 'fd'"
if [ "$SECONDS" -lt 20 ]; then ok; else bad "the fd:: source took ${SECONDS}s"; fi
run fd-helper 1 timeout 30 "$SMI" libs add 'fd::7'
has_err "names the git remote helper 'fd'"
run ext-helper 1 timeout 30 "$SMI" libs add "ext::sh -c touch% $WORK/escaped_ext"
has_err "names the git remote helper 'ext'"
nothing_escaped
run ftp-protocol 1 timeout 30 "$SMI" libs add 'ftp://127.0.0.1/x.git@v1.0.0'
has_err "cannot reach the library source"
# a git that never answers is stopped at --timeout
mkdir -p slowbin && printf '#!/bin/sh\nsleep 60\n' > slowbin/git && chmod +x slowbin/git
SECONDS=0
PATH="$WORK/g/slowbin:$PATH" run slow-git 1 timeout 40 "$SMI" --timeout 2 libs add "file://$WORK/nothing@v1.0.0"
has_err "did not finish within 2 s"
if [ "$SECONDS" -lt 20 ]; then ok; else bad "the time limit did not hold: ${SECONDS}s"; fi
if [ -z "$(find . -name '.smi-tmp-*')" ]; then ok; else bad "a stopped add left a temporary folder"; fi
cd ..

finish
