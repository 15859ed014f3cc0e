# SPDX-License-Identifier: MIT
# Library metadata held to the library: the git commit is read only from
# inside the checkout, and provenance never hashes what a symlink out of the library points to.
# One test per denial; each passed the data through (or hung) before the fix.
source "${SMI_SOURCE_DIR:?}/tests/cli/lib.sh"   # run / has_out / has_err / finish; cd's to a temp dir

SHA=0123456789abcdef0123456789abcdef01234567
# lib DIR NAME: a library folder (manifest + init.lua), no git
lib() {
  mkdir -p "$1"
  printf 'name = "%s"\nversion = "1.0.0"\n' "$2" > "$1/smi-lib.lua"
  printf 'return {}\n' > "$1/init.lua"
}
commit_of() { "$SMI" --lib "$1" -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'; }

# a "gitdir:" file pointing out of the library
lib libs/a a
mkdir -p elsewhere/gd && echo "$SHA" > elsewhere/gd/HEAD
echo "gitdir: $WORK/elsewhere/gd" > libs/a/.git
run "gitdir: file pointing out" 0 "$SMI" --lib libs/a -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=nil"
# .git itself a symlink to a git folder out of the library
lib libs/b b
ln -s "$WORK/elsewhere/gd" libs/b/.git
run ".git symlinked out" 0 "$SMI" --lib libs/b -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=nil"
# commondir pointing out
lib libs/c c
mkdir -p libs/c/.git elsewhere/common/refs/heads
echo "ref: refs/heads/main" > libs/c/.git/HEAD
echo "$WORK/elsewhere/common" > libs/c/.git/commondir
echo "$SHA" > elsewhere/common/refs/heads/main
run "commondir pointing out" 0 "$SMI" --lib libs/c -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=nil"
# a ref climbing out of the git folder
lib libs/d d
mkdir -p libs/d/.git && echo "$SHA" > elsewhere/token
echo "ref: ../../../elsewhere/token" > libs/d/.git/HEAD
run "ref climbing out" 0 "$SMI" --lib libs/d -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=nil"
# HEAD a FIFO: reading it would hang the run before any script code
lib libs/e e
mkdir -p libs/e/.git && mkfifo libs/e/.git/HEAD
run "HEAD is a FIFO" 0 timeout 10 "$SMI" --lib libs/e -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=nil"
# the honest case still works: a .git folder inside, loose ref
lib libs/f f
mkdir -p libs/f/.git/refs/heads && echo "ref: refs/heads/main" > libs/f/.git/HEAD && echo "$SHA" > libs/f/.git/refs/heads/main
run "git inside the library" 0 "$SMI" --lib libs/f -e 'print("commit=" .. tostring(smi.libraries()[1].commit))'
out_is "commit=$SHA"

# provenance: a symlink out of the library is hashed by its link text, never its target
echo "secret-data" > elsewhere/secret.txt
secret_hash=$(sha256sum elsewhere/secret.txt | cut -c1-64)
lib libs/g g
ln -s "$WORK/elsewhere/secret.txt" libs/g/leak.txt
ln -s init.lua libs/g/inside_link.lua
ln -s "$WORK/elsewhere/missing" libs/g/dangling
run "provenance of a link out" 0 "$SMI" --lib libs/g -e \
    'local f = smi.provenance().libraries[1].files; print(f["leak.txt"]); print(f["inside_link.lua"]); print(f["dangling"])'
lacks_out "$secret_hash"
has_out "symlink:"
has_out "$(sha256sum libs/g/init.lua | cut -c1-64)"   # a link inside is hashed by content, as before
lib libs/h h
ln -s /dev/zero libs/h/zero
run "provenance of a link to /dev/zero" 0 timeout 10 "$SMI" --lib libs/h -e 'print(smi.provenance().libraries[1].files["zero"])'
has_out "symlink:"

# the manifest itself: a symlink out of the library is not read (a FIFO or device manifest is
# not taken for a library at all, before and after)
printf 'name = "stolen"\nversion = "1.0.0"\n' > elsewhere/manifest.lua
mkdir -p libs/j && ln -s "$WORK/elsewhere/manifest.lua" libs/j/smi-lib.lua
run "manifest linked out of the library" 1 "$SMI" --lib libs/j -e 'print(1)'
has_err "not a regular file inside the library folder"

finish
