# SPDX-License-Identifier: MIT
# Library sharing between two teams on one machine, through a team registry that is a local git
# repository (no server): team A publishes; team B finds a library by name, adds it with a range,
# updates within the range after A publishes a new version, and tampers with an installed file:
# the study stops and names the file. Also: smi-project.json written by libs add and read by
# libs sync, NAME@VERSION reusing the recorded source, a published version never replaced,
# checksums and commits of the index verified on install, `smi-lua test LIB` resolving the
# library's own requirements, and registry addresses held to git's protocol allow-list.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir

source "${SMI_SOURCE_DIR}/tests/libs/git_release.sh"   # gitc, release
lock_version() {  # lock_version NAME: the version smi-lock.json pins
  /usr/bin/python3 -c "import json,sys; print([l['version'] for l in json.load(open('smi-lock.json'))['libraries'] if l['name']==sys.argv[1]][0])" "$1"
}

R=$WORK/teamA-repos
export DESC="converts units, by team A"
release "$R/unitconv" unitconv 1.0.0 ""
release "$R/unitconv" unitconv 2.0.0 ""
release "$R/refcrit" refcrit 1.2.0 '"unitconv >= 2.0, < 3"'   # no `sources`: found through the registry
U=file://$R/unitconv
C=file://$R/refcrit
git init -q --bare "$WORK/registry.git"
REG=file://$WORK/registry.git

# --- team A publishes -----------------------------------------------------------------------------
mkdir -p teamA && cd teamA
run registry-name 0 "$SMI" libs registry team "$REG"
has_out "smi-project.json: registry team = $REG"
run publish-unitconv 0 "$SMI" libs publish team "$U@v2.0.0"
has_out "published unitconv 2.0.0 ($U at v2.0.0, commit $(git -C "$R/unitconv" rev-parse --short=12 'v2.0.0^{commit}')"
run publish-refcrit 0 "$SMI" libs publish team "$C@v1.2.0"
run publish-again 1 "$SMI" libs publish team "$U@v2.0.0"
has_err "unitconv 2.0.0 is published already in $REG"
has_err "a published version is never replaced"
run publish-folder 1 "$SMI" libs publish team "$R/refcrit"
has_err "names no version tag"
cd ..
# the index: one file per library, one JSON line per version, with the folder checksum
idx=$(git --git-dir="$WORK/registry.git" show HEAD:index/unitconv)
if [ "$(printf '%s\n' "$idx" | wc -l)" = 1 ] && printf '%s' "$idx" | grep -q '"checksum":"sha256:' \
   && printf '%s' "$idx" | grep -q "\"commit\":\"$(git -C "$R/unitconv" rev-parse 'v2.0.0^{commit}')\""; then ok
else bad "registry index/unitconv: $idx"; fi

# --- team B finds and adds by name with a range ------------------------------------------------------
mkdir -p teamB && cd teamB
run search-none-yet 1 "$SMI" libs search unit
has_err "names no registry"
"$SMI" libs registry team "$REG" > /dev/null
run search 0 "$SMI" libs search UNITS
has_out "unitconv 2.0.0  converts units, by team A  [team; versions: 2.0.0]"
run add-by-range 0 "$SMI" libs add 'refcrit@^1.2'
has_out "installed refcrit 1.2.0 from $C at v1.2.0"
has_out "installed unitconv 2.0.0 from $U at v2.0.0"
has_out "required by refcrit"
if grep -q '"refcrit"' smi-project.json && grep -q '"version": "^1.2"' smi-project.json && grep -q '"registry": "team"' smi-project.json
then ok; else bad "smi-project.json: $(cat smi-project.json)"; fi
cat > study.lua <<'LUA'
print("SAW", require("refcrit").version, require("unitconv").version)
LUA
run study-1 0 "$SMI" study.lua
has_out "SAW	1.2.0	2.0.0"

# --- team A publishes new versions; team B updates within its range ----------------------------------
release "$R/unitconv" unitconv 2.1.0 ""
release "$R/unitconv" unitconv 3.0.0 ""
release "$R/refcrit" refcrit 1.3.0 '"unitconv >= 2.1, < 3"'
release "$R/refcrit" refcrit 2.0.0 '"unitconv >= 3"'
for v in 2.1.0 3.0.0; do (cd ../teamA && "$SMI" libs publish team "$U@v$v" > /dev/null) || bad "publish unitconv $v"; done
for v in 1.3.0 2.0.0; do (cd ../teamA && "$SMI" libs publish team "$C@v$v" > /dev/null) || bad "publish refcrit $v"; done
run update 0 "$SMI" libs update
has_out "updating refcrit 1.2.0 -> 1.3.0"
has_out "installed unitconv 2.1.0"
if [ "$(lock_version refcrit)" = 1.3.0 ] && [ "$(lock_version unitconv)" = 2.1.0 ]; then ok; else bad "lock after update: $(cat smi-lock.json | head -c 600)"; fi
run update-again 0 "$SMI" libs update refcrit
has_out "refcrit 1.3.0: up to date (the highest of ^1.2"
run study-2 0 "$SMI" study.lua
has_out "SAW	1.3.0	2.1.0"

# --- team B tampers with an installed file: the study stops and names it -----------------------------
echo '-- changed' >> smi-libs/unitconv/2.1.0/init.lua
run tampered 1 "$SMI" study.lua
has_err "library unitconv 2.1.0 at"
has_err "file 'init.lua' differs from smi-lock.json"
has_err "restore it with: smi-lua libs sync"
lacks_out SAW
run repair 0 "$SMI" libs sync
has_out "restored   unitconv 2.1.0"
run study-3 0 "$SMI" study.lua
has_out "SAW	1.3.0	2.1.0"
cd ..

# --- a teammate with only smi-project.json: sync resolves it -----------------------------------------
mkdir -p teamB2 && cp teamB/smi-project.json teamB2/ && cd teamB2
run sync-from-manifest 0 "$SMI" libs sync
has_out "installed refcrit 1.3.0"
if [ "$(lock_version unitconv)" = 2.1.0 ]; then ok; else bad "sync from smi-project.json: $(head -c 600 smi-lock.json)"; fi
cd ..

# --- checksums and commits recorded in the index are verified on install -----------------------------
good=$(git -C "$R/unitconv" rev-parse 'v2.1.0^{commit}')
gitc "$R/unitconv" checkout -q "$good"
echo '-- moved' >> "$R/unitconv/init.lua" && gitc "$R/unitconv" commit -qam moved && gitc "$R/unitconv" tag -f v2.1.0
mkdir -p teamC && cd teamC
"$SMI" libs registry team "$REG" > /dev/null
run moved-tag 1 "$SMI" libs add 'unitconv@2.1.0'
has_err "but the registry $REG recorded commit $good when it was published (the tag was moved)"
gitc "$R/unitconv" tag -f v2.1.0 "$good"
# an index line whose checksum does not match the files
git clone -q "$WORK/registry.git" ../regwork
sed -i '/"version":"3.0.0"/s/"checksum":"sha256:[0-9a-f]*"/"checksum":"sha256:0000"/' ../regwork/index/unitconv
gitc ../regwork commit -qam "bad checksum" && gitc ../regwork push -q origin HEAD
run bad-checksum 1 "$SMI" libs add 'unitconv@3.0.0'
has_err "but the registry $REG recorded sha256:0000"
if [ ! -e smi-lock.json ] && [ -z "$(find smi-libs -mindepth 1 2>/dev/null)" ]; then ok; else bad "a refused install left files"; fi
cd ..

# --- NAME@VERSION reuses the recorded source -----------------------------------------------------------
mkdir -p teamD && cd teamD
run add-url 0 "$SMI" libs add "$U@v1.0.0"
run add-name-version 0 "$SMI" libs add unitconv@2.0.0
has_out "installed unitconv 2.0.0 from $U at v2.0.0"
if grep -q "\"source\": \"$U\"" smi-project.json && grep -q '"version": "^2.0.0"' smi-project.json; then ok; else bad "$(cat smi-project.json)"; fi
run add-unknown 1 "$SMI" libs add nosuchlib@1.0.0
has_err "library 'nosuchlib' has no source recorded in smi-project.json or smi-lock.json, and the project names no registry"
cd ..

# --- smi-lua test LIB resolves the library's own requirements -----------------------------------------
mkdir -p usesconv/tests
printf 'name = "usesconv"\nversion = "0.1.0"\nrequires = {"unitconv >= 2.0, < 3"}\nsources = {unitconv = "%s"}\n' "$U" > usesconv/smi-lib.lua
printf 'return {}\n' > usesconv/init.lua
printf 'assert(require("unitconv").version == "2.1.0")\nprint("1 passed, 0 failed")\n' > usesconv/tests/test_conv.lua
run test-lib 0 "$SMI" test usesconv
has_out "installed unitconv 2.1.0 from $U"
has_out "1 passed, 0 failed"
run test-lib-again 0 "$SMI" test usesconv
lacks_out "installed"

# --- registry addresses: file, https and ssh only --------------------------------------------------------
mkdir -p teamE && cd teamE
run registry-helper 1 "$SMI" libs registry evil 'ext::sh -c touch% /tmp/smi-registry-escaped'
has_err "names the git remote helper 'ext'"
if [ ! -e /tmp/smi-registry-escaped ]; then ok; else bad "a registry address ran a program"; fi
cd ..

finish
