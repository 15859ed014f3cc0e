#!/bin/bash
# SPDX-License-Identifier: MIT
# packaging/spdx_headers.sh on a planted tree: --check names a file without the licence tag and
# fails; the fix adds the tag on line 1 (line 2 after "#!"), keeps the rest and the execute bit,
# leaves fixtures alone, and a second run changes nothing.
set -u
script=$SMI_SOURCE_DIR/packaging/spdx_headers.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mkdir -p "$work/a/fixtures"
printf 'int f();\n' > "$work/a/x.hpp"
printf '#!/bin/bash\necho hi\n' > "$work/a/run.sh" && chmod 755 "$work/a/run.sh"
printf 'return 1\n' > "$work/a/m.lua"
printf 'line 1\n' > "$work/a/fixtures/f.lua"
out=$(bash "$script" --check "$work") && fail "--check passed a tree without tags"
grep -q "no licence tag: a/x.hpp" <<< "$out" || { echo "$out"; fail "--check did not name a/x.hpp"; }
grep -q "fixtures" <<< "$out" && fail "--check named a fixture"
bash "$script" "$work" || fail "adding the tags"
[ "$(head -n 1 "$work/a/x.hpp")" = "// SPDX-License-Identifier: MIT" ] || fail "C++ tag: $(head -n 1 "$work/a/x.hpp")"
[ "$(sed -n 2p "$work/a/run.sh")" = "# SPDX-License-Identifier: MIT" ] || fail "shell tag not after #!"
[ "$(head -n 1 "$work/a/run.sh")" = "#!/bin/bash" ] || fail "the #! line moved"
[ -x "$work/a/run.sh" ] || fail "the execute bit was lost"
[ "$(head -n 1 "$work/a/m.lua")" = "-- SPDX-License-Identifier: MIT" ] || fail "Lua tag"
[ "$(cat "$work/a/fixtures/f.lua")" = "line 1" ] || fail "a fixture was changed"
before=$(cat "$work"/a/*.hpp "$work"/a/*.sh "$work"/a/*.lua | md5sum)
bash "$script" "$work" && bash "$script" --check "$work" > /dev/null || fail "--check after the fix"
[ "$before" = "$(cat "$work"/a/*.hpp "$work"/a/*.sh "$work"/a/*.lua | md5sum)" ] || fail "a second run changed files"
echo "ok   spdx_headers.sh finds, adds and keeps the licence tags"
