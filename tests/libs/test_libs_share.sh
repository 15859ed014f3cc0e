# SPDX-License-Identifier: MIT
# Sharing libraries between teams, end to end and without network: team A's
# libraries are git repositories made here with tags, reached through file:// URLs.
# libs add (with a dependency chain), smi-lock.json, sync after deleting the tree (same
# commits, same bytes), sync --check after tampering, side-by-side versions chosen by the
# lockfile, libs tree / outdated / remove, pack and add of an archive, hostile archives, and
# each bad input: unreachable source, missing tag, tag and manifest disagreeing, unsatisfiable
# requirement, hand-edited lockfile. Nothing may be half-installed after a failure.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir

source "${SMI_SOURCE_DIR}/tests/libs/git_release.sh"   # gitc, release
files_sha() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs sha256sum); }
no_leftovers() {  # no temporary folder and no half-installed library in the tree $1
  if [ -z "$(find "$1" -name '.smi-tmp-*' 2>/dev/null)" ]; then ok; else bad "temporary folder left in $1"; fi
}

R=$WORK/remote
release "$R/unitconv" unitconv 1.0.0 ""
release "$R/unitconv" unitconv 2.0.0 ""
mkdir -p "$R/unitconv/convert" && printf 'return { mm_to_m = function(x) return x / 1000 end }\n' > "$R/unitconv/convert/length.lua"
gitc "$R/unitconv" add -A && gitc "$R/unitconv" commit -q --amend -m "release 2.0.0" && gitc "$R/unitconv" tag -f v2.0.0
U=file://$R/unitconv
release "$R/refcrit" refcrit 0.9.0 '"unitconv >= 5"' "unitconv = \"$U\""
release "$R/refcrit" refcrit 1.2.0 '"unitconv >= 2.0, < 3", "smi-lua >= 0.1"' "unitconv = \"$U\""
release "$R/refcrit" refcrit 1.2.9 '"unitconv >= 2.0, < 3"' "unitconv = \"$U\"" v1.3.0   # a tag that lies
gitc "$R/refcrit" checkout -q v1.2.0
C=file://$R/refcrit
r_commit=$(git -C "$R/refcrit" rev-parse 'v1.2.0^{commit}')
u_commit=$(git -C "$R/unitconv" rev-parse 'v2.0.0^{commit}')

# --- team B adds refcrit 1.2.0: its requirement unitconv comes from the source it names -----
mkdir -p teamB && cd teamB
run add-chain 0 "$SMI" libs add "$C@v1.2.0"
has_out "installed refcrit 1.2.0 from $C at v1.2.0 (${r_commit:0:12}) into"
has_out "installed unitconv 2.0.0 from $U at v2.0.0 (${u_commit:0:12})"
has_out "required by refcrit"
has_out "smi-lock.json: 2 libraries locked"
if [ -f smi-libs/refcrit/1.2.0/init.lua ] && [ -f smi-libs/unitconv/2.0.0/convert/length.lua ] && [ ! -e smi-libs/refcrit/1.2.0/.git ]; then ok
else bad "tree not as expected: $(find smi-libs | head -20)"; fi
if grep -q "\"commit\": \"$r_commit\"" smi-lock.json && grep -q "\"commit\": \"$u_commit\"" smi-lock.json \
   && grep -q "\"source\": \"$U\"" smi-lock.json \
   && grep -q "\"init.lua\": \"$(sha256sum smi-libs/unitconv/2.0.0/init.lua | cut -c1-64)\"" smi-lock.json; then ok
else bad "smi-lock.json lacks commits, sources or hashes: $(head -c 1500 smi-lock.json)"; fi
no_leftovers smi-libs

# a study run in the project folder sees the tree; results.json records source and commit
cat > study.lua <<'LUA'
local study = require "smi.study"
local s = study.new{name = "b", out = smi.out_dir}
s:step("use", function() return {v = require("unitconv").version, r = require("refcrit").version} end)
s:run()
LUA
run study 0 "$SMI" --quiet --out out study.lua
if grep -q "\"source\": *\"$C\"" out/results.json && grep -q "\"commit\": *\"$r_commit\"" out/results.json \
   && grep -q "\"commit\": *\"$u_commit\"" out/results.json && grep -q '"v": *"2.0.0"' out/results.json; then ok
else bad "results.json lacks the libraries' source and commit: $(head -c 1500 out/results.json)"; fi
run tree 0 "$SMI" libs tree
has_out "refcrit 1.2.0  $C @ ${r_commit:0:12}"
has_out "|-- unitconv 2.0.0  (requires >= 2.0, < 3)"
has_out "\`-- smi-lua"
run list 0 "$SMI" libs
has_out "unitconv  2.0.0    ${u_commit:0:12}"

# --- anyone syncs: same files, byte for byte, same lockfile ----------------------------------
files_sha smi-libs > ../before.sha
cp smi-lock.json ../lock.before
rm -rf smi-libs
# a study does not start on a lockfile whose libraries are not installed
run study-unsynced 1 "$SMI" --quiet --out out2 study.lua
has_err "smi-lock.json pins refcrit 1.2.0, but"
has_err "is not installed; run smi-lua libs sync"
run sync 0 "$SMI" libs sync
has_out "installed  refcrit 1.2.0 from $C (${r_commit:0:12})"
has_out "every file matches its SHA-256"
files_sha smi-libs > ../after.sha
if cmp -s ../before.sha ../after.sha && cmp -s smi-lock.json ../lock.before; then ok; else bad "sync restored other bytes"; fi
# the results file written before the tree was deleted matches the synced tree
run verify-after-sync 0 "$SMI" verify out/results.json
has_out "ok       unitconv 2.0.0"
run sync-again 0 "$SMI" libs sync
has_out "ok         unitconv 2.0.0 (3 files)"
run check 0 "$SMI" libs sync --check
# a moved tag does not change what sync restores: it fetches the locked commit
gitc "$R/unitconv" tag -f v2.0.0 v1.0.0
rm -rf smi-libs/unitconv
run sync-moved-tag 0 "$SMI" libs sync
files_sha smi-libs > ../after2.sha
if cmp -s ../before.sha ../after2.sha; then ok; else bad "sync followed the moved tag"; fi
gitc "$R/unitconv" tag -f v2.0.0 "$u_commit"

# --- --check after tampering with one file names the library and the file ---------------------
printf 'return { version = "2.0.0", hacked = true }\n' > smi-libs/unitconv/2.0.0/init.lua
run check-tampered 1 "$SMI" libs sync --check
has_err "library unitconv 2.0.0 at"
has_err "file 'init.lua' differs from smi-lock.json"
lacks_out "installed"
echo 'x' > smi-libs/refcrit/1.2.0/extra.lua
run check-added 1 "$SMI" libs sync --check
has_err "library refcrit 1.2.0 at"
has_err "file 'extra.lua' is not in smi-lock.json"
# a study does not run on the changed copies; sync restores them from their sources
run study-tampered 1 "$SMI" --quiet --out out3 study.lua
has_err "file 'init.lua' differs from smi-lock.json"
has_err "restore it with: smi-lua libs sync"
run sync-repairs 0 "$SMI" libs sync
has_out "repairing  refcrit 1.2.0: file 'extra.lua' is not in smi-lock.json"
has_out "restored   unitconv 2.0.0 from $U"
files_sha smi-libs > ../repaired.sha
if cmp -s ../before.sha ../repaired.sha; then ok; else bad "sync did not restore the changed libraries byte for byte"; fi
rm -rf smi-libs/unitconv
run check-missing 1 "$SMI" libs sync --check
has_err "library unitconv 2.0.0 is not installed"
run sync-restores 0 "$SMI" libs sync
run check-restored 0 "$SMI" libs sync --check

# --- a hand-edited lockfile is refused, naming the library ---------------------------------------
cp smi-lock.json ../lock.good
sed -i 's/"version": "2.0.0"/"version": "2.0.1"/' smi-lock.json
run lock-edited 1 "$SMI" libs sync
has_err "library 'unitconv' 2.0.1 was edited by hand"
has_err "git checkout smi-lock.json"
run lock-edited-study 1 "$SMI" --quiet --out out study.lua
has_err "was edited by hand"
cp ../lock.good smi-lock.json
python3 - <<'PY'
import json
d = json.load(open("smi-lock.json"))
d["libraries"] = [l for l in d["libraries"] if l["name"] != "unitconv"]
json.dump(d, open("smi-lock.json", "w"), indent=2)
PY
run lock-entry-dropped 1 "$SMI" libs sync --check
has_err "was edited by hand: a library entry was added or removed"
cp ../lock.good smi-lock.json

# --- outdated: newer tags, and an unreachable source ---------------------------------------------
release "$R/unitconv" unitconv 2.1.0 ""
run outdated 0 "$SMI" libs outdated
has_out "unitconv 2.0.0: newer at $U: v2.1.0"
mv "$R/refcrit" "$R/refcrit.away"
run outdated-unreachable 0 "$SMI" libs outdated
has_out "refcrit 1.2.0: cannot check, the source cannot be reached"
has_out "1 source could not be reached"
mv "$R/refcrit.away" "$R/refcrit"

# --- remove ----------------------------------------------------------------------------------------
run remove-required 1 "$SMI" libs remove unitconv
has_err "refcrit 1.2.0 requires 'unitconv >= 2.0, < 3': remove refcrit first"
cd ..

# --- bad inputs: each a clear error, nothing half-installed ---------------------------------------
mkdir -p bad && cd bad
run unreachable 1 "$SMI" libs add "file://$WORK/nothere@v1.0.0"
has_err "cannot reach the library source 'file://$WORK/nothere': git clone failed: '$WORK/nothere' does not appear to be a git repository"
if [ ! -e smi-libs ] && [ ! -e smi-lock.json ]; then ok; else bad "a failed add left smi-libs/ or smi-lock.json"; fi
run missing-tag 1 "$SMI" libs add "$U@v9.9.9"
has_err "has no tag, branch or commit 'v9.9.9'; its version tags: v2.1.0, v2.0.0, v1.0.0"
run ref-option 1 "$SMI" libs add "$U@--upload-pack=true"
has_err "is not a tag, branch or commit name (it starts with '-')"
run tag-lies 1 "$SMI" libs add "$C@v1.3.0"
has_err "at tag v1.3.0 holds refcrit version 1.2.9 in its smi-lib.lua, not 1.3.0"
run unsatisfiable 1 "$SMI" libs add "$C@v0.9.0"
has_err "no version of unitconv at $U satisfies every requirement on it (refcrit 0.9.0 requires 'unitconv >= 5'); versions seen: v2.1.0, v2.0.0, v1.0.0"
if [ ! -e smi-lock.json ] && [ -z "$(find smi-libs -mindepth 1 2>/dev/null)" ]; then ok; else bad "a failed add left files: $(find . | head)"; fi
run add-by-commit 0 "$SMI" libs add "$U@$u_commit"
has_out "installed unitconv 2.0.0 from $U at $u_commit"
# asking for a version that a locked library cannot use is refused
cd .. && mkdir -p bad2 && cd bad2
"$SMI" libs add "$C@v1.2.0" > /dev/null 2>&1
run pinned-conflict 1 "$SMI" libs add "$U@v1.0.0"
has_err "you asked for unitconv 1.0.0, but refcrit 1.2.0 requires 'unitconv >= 2.0, < 3'"
no_leftovers smi-libs
cd ..

# --- side-by-side versions in one tree; the lockfile of each project chooses ----------------------
mkdir -p p1 p2 && cd p1
run into-1 0 "$SMI" libs add "$U@v2.0.0" --into ../shared
cd ../p2
run into-2 0 "$SMI" libs add "$C@v1.2.0" --into ../shared
cd ..
if [ -d shared/unitconv/2.0.0 ] && [ -d shared/unitconv/2.1.0 ]; then ok; else bad "side-by-side versions missing: $(ls shared/unitconv)"; fi
# a tree outside the project is read only when the user names it
(cd p1 && "$SMI" -e 'print("SAW", require("unitconv").version)') > .o0 2>&1
if grep -q "outside the project folder; a study reads a tree outside its folder only when you give it yourself: --lib" .o0
then ok; else bad "a lockfile's outside tree was read without --lib: $(cat .o0)"; fi
(cd p1 && "$SMI" --lib ../shared -e 'print("SAW", require("unitconv").version)') > .o1 2>&1
(cd p2 && "$SMI" --lib ../shared -e 'print("SAW", require("unitconv").version)') > .o2 2>&1
if grep -q "SAW	2.0.0" .o1 && grep -q "SAW	2.1.0" .o2; then ok; else bad "lockfiles did not choose: $(cat .o1 .o2)"; fi
# without a lockfile: the highest version satisfying every requirement
run highest 0 "$SMI" --lib shared -e 'print("SAW", require("unitconv").version)'
has_out "SAW	2.1.0"
mkdir -p oldfan && printf 'name = "oldfan"\nversion = "1.0.0"\nrequires = {"unitconv < 2.1"}\n' > oldfan/smi-lib.lua
run highest-satisfying 0 "$SMI" --lib shared --lib oldfan -e 'print("SAW", require("unitconv").version)'
has_out "SAW	2.0.0"
printf 'name = "oldfan"\nversion = "1.0.0"\nrequires = {"unitconv > 9"}\n' > oldfan/smi-lib.lua
run none-satisfying 1 "$SMI" --lib shared --lib oldfan -e 'print(1)'
has_err "(versions of unitconv in the library tree: 2.1.0, 2.0.0)"
# two versions in one study are still refused
run two-versions 1 "$SMI" --lib shared --lib shared/unitconv/2.0.0 -e 'print(1)'
has_err "two copies of library 'unitconv'"
# remove a side-by-side version the lockfile does not use, then the locked one
cd p1
run remove-side-unnamed 1 "$SMI" libs remove unitconv@2.1.0
has_err "outside the project folder; libs changes a tree outside the project only when you name it: add --into ../shared"
run remove-side 0 "$SMI" libs remove unitconv@2.1.0 --into ../shared
if [ ! -e ../shared/unitconv/2.1.0 ] && [ -d ../shared/unitconv/2.0.0 ]; then ok; else bad "remove of a side version"; fi
run remove-locked 0 "$SMI" libs remove unitconv --into ../shared
has_out "removed unitconv 2.0.0 (folder and smi-lock.json entry)"
if [ ! -e ../shared/unitconv ] && ! grep -q unitconv smi-lock.json; then ok; else bad "remove left unitconv"; fi
cd ..

# --- pack, and add of the archive --------------------------------------------------------------
gitc "$R/unitconv" checkout -q v2.0.0
run pack 0 "$SMI" libs pack "$R/unitconv"
has_out "packed unitconv 2.0.0: 3 files and smi-pack.sha256 into unitconv-2.0.0.tar.gz"
cp unitconv-2.0.0.tar.gz first.tar.gz
run pack-again 0 "$SMI" libs pack "$R/unitconv"
if cmp -s first.tar.gz unitconv-2.0.0.tar.gz; then ok; else bad "pack is not byte-reproducible"; fi
mkdir -p unpacked && tar -xzf unitconv-2.0.0.tar.gz -C unpacked
if (cd unpacked/unitconv-2.0.0 && sha256sum -c --quiet smi-pack.sha256); then ok; else bad "smi-pack.sha256 does not check with sha256sum -c"; fi
mkdir -p p3 && cd p3
run add-archive 0 "$SMI" libs add ../unitconv-2.0.0.tar.gz
has_out "installed unitconv 2.0.0 from ../unitconv-2.0.0.tar.gz ("
if grep -q "\"commit\": \"sha256:$(sha256sum ../unitconv-2.0.0.tar.gz | cut -c1-64)\"" smi-lock.json \
   && cmp -s smi-libs/unitconv/2.0.0/convert/length.lua "$R/unitconv/convert/length.lua" && [ ! -e smi-libs/unitconv/2.0.0/smi-pack.sha256 ]; then ok
else bad "archive install: $(cat smi-lock.json | head -c 800)"; fi
rm -rf smi-libs
run sync-archive 0 "$SMI" libs sync
cd ..
# an archive altered after packing
python3 - <<'PY'
import io, tarfile
src = tarfile.open("unitconv-2.0.0.tar.gz")
out = tarfile.open("altered.tar.gz", "w:gz")
for m in src.getmembers():
    data = src.extractfile(m).read() if m.isfile() else None
    if m.name.endswith("/init.lua"):
        data = b"return { evil = true }\n"; m.size = len(data)
    out.addfile(m, io.BytesIO(data) if data is not None else None)
out.close()
PY
mkdir -p p4 && cd p4
run add-altered 1 "$SMI" libs add ../altered.tar.gz
has_err "file 'init.lua' does not match its SHA-256 in smi-pack.sha256"
cd ..

# --- a local folder (not a git checkout) as the source: copied, and copied again by sync ---------
mkdir -p plain/helpers && printf 'name = "plain"\nversion = "0.3.0"\n' > plain/smi-lib.lua
printf 'return 42\n' > plain/helpers/answer.lua
mkdir -p p7 && cd p7
run add-folder 0 "$SMI" libs add ../plain
has_out "installed plain 0.3.0 from ../plain into"
rm -rf smi-libs
run sync-folder 0 "$SMI" libs sync
if cmp -s smi-libs/plain/0.3.0/helpers/answer.lua ../plain/helpers/answer.lua; then ok; else bad "folder source not restored"; fi
printf 'return 43\n' > ../plain/helpers/answer.lua
rm -rf smi-libs
run sync-folder-changed 1 "$SMI" libs sync
has_err "library plain 0.3.0 fetched from ../plain: file 'helpers/answer.lua' differs from smi-lock.json"
cd ..

# --- hostile archives: .., absolute, symlink, device members are refused by name ------------------
python3 - <<'PY'
import io, tarfile
def make(path, kind):
    t = tarfile.open(path, "w:gz")
    def add(name, data=b"x", type=tarfile.REGTYPE, link=""):
        i = tarfile.TarInfo(name); i.type = type; i.linkname = link
        i.size = len(data) if type == tarfile.REGTYPE else 0
        t.addfile(i, io.BytesIO(data) if type == tarfile.REGTYPE else None)
    add("evil-1.0.0/smi-lib.lua", b'name = "evil"\nversion = "1.0.0"\n')
    if kind == "dotdot": add("evil-1.0.0/../../escaped.lua")
    if kind == "abs": add("/tmp/smi-abs-escaped.lua")
    if kind == "symlink": add("evil-1.0.0/leak.lua", type=tarfile.SYMTYPE, link="/etc/passwd")
    if kind == "hardlink": add("evil-1.0.0/hard.lua", type=tarfile.LNKTYPE, link="/etc/passwd")
    if kind == "device": add("evil-1.0.0/dev.lua", type=tarfile.CHRTYPE)
    t.close()
for k in ["dotdot", "abs", "symlink", "hardlink", "device"]:
    make(f"hostile-{k}.tar.gz", k)
PY
mkdir -p p5 && cd p5
run hostile-dotdot 1 "$SMI" libs add ../hostile-dotdot.tar.gz
has_err "member 'evil-1.0.0/../../escaped.lua' has a '..' component"
run hostile-abs 1 "$SMI" libs add ../hostile-abs.tar.gz
has_err "member '/tmp/smi-abs-escaped.lua' has an absolute name"
run hostile-symlink 1 "$SMI" libs add ../hostile-symlink.tar.gz
has_err "member 'evil-1.0.0/leak.lua' is a symbolic link (to '/etc/passwd')"
run hostile-hardlink 1 "$SMI" libs add ../hostile-hardlink.tar.gz
has_err "member 'evil-1.0.0/hard.lua' is a hard link"
run hostile-device 1 "$SMI" libs add ../hostile-device.tar.gz
has_err "member 'evil-1.0.0/dev.lua' is a character device"
if [ ! -e "$WORK/escaped.lua" ] && [ ! -e /tmp/smi-abs-escaped.lua ] && [ ! -e smi-lock.json ] \
   && [ -z "$(find smi-libs -mindepth 1 2>/dev/null)" ]; then ok; else bad "a hostile archive left files"; fi
cd ..

# --- git runs without the user's configuration and hooks; links in a repository are refused -----
mkdir -p evilhome/hooks
printf '#!/bin/sh\ntouch %s/HOOK_RAN\n' "$WORK" > evilhome/hooks/post-checkout
chmod +x evilhome/hooks/post-checkout
printf '[core]\n\thooksPath = %s/evilhome/hooks\n' "$WORK" > evilhome/.gitconfig
mkdir -p p6 && cd p6
HOME=$WORK/evilhome run no-hooks 0 "$SMI" libs add "$U@v2.0.0"
if [ ! -e "$WORK/HOOK_RAN" ]; then ok; else bad "a git hook from the user's configuration ran"; fi
release "$R/linky" linky 1.0.0 ""
ln -s /etc/passwd "$R/linky/leak.lua" && gitc "$R/linky" add -A && gitc "$R/linky" commit -q -m link && gitc "$R/linky" tag v1.0.1
sed -i 's/1.0.0/1.0.1/' "$R/linky/smi-lib.lua" && gitc "$R/linky" commit -qam v && gitc "$R/linky" tag -f v1.0.1
run repo-symlink 1 "$SMI" libs add "file://$R/linky@v1.0.1"
has_err "holds a symbolic link, 'leak.lua'"
cd ..

finish
