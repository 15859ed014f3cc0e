#!/usr/bin/env python3
"""Moves the kernels' namespaces to one scheme and qualifies their uses (issue 18).

    host/kernels/core       smi                          (unchanged: the shared vocabulary;
                                                          components smi::cancel, ::csv, ::json, ...)
    host/kernels/stats      smi -> smi::stats,  smi::detail -> smi::stats::detail
    host/kernels/surrogate  smi::<c> -> smi::surrogate::<c>   for c in kriging doe delta polyfit
                                                          propagate screen (nested: flat would clash,
                                                          e.g. delta::Options/screen::Options, kriging::fit/polyfit::fit)
    host/kernels/improve    smi::improve  (unchanged)
    host/kernels/eval       smi::eval     (unchanged)

What it rewrites, in code only (comments and string literals are masked; `// namespace smi`
closing comments of the moved files follow their namespace):
  1. `namespace smi {` / `namespace smi::detail {` in host/kernels/stats files, and
     `namespace smi::<c>` in host/kernels/surrogate files, to the new namespace.
  2. everywhere: `smi::<stats symbol>` -> `smi::stats::<symbol>`, `smi::detail::` -> `smi::stats::detail::`,
     `smi::<c>` -> `smi::surrogate::<c>` (so `using smi::Kde;`, `using namespace smi::kriging;` follow);
     the old parallel loops `[smi::]detail::parallel_for/_blocks` -> `smi::pool::parallel_for/_blocks`
     (the codecs branch replaced stats/parallel.hpp and surrogate/parallel.hpp by core's thread pool;
     their #include needs a hand edit to "kernels/core/thread_pool.hpp").
  3. outside the moved area, in files that open a `smi` namespace or use `using namespace smi`:
     a bare `<c>::` becomes `surrogate::<c>::`, and an unqualified stats symbol (a type or constant
     anywhere, a function where it is called: `name(` or `name<`) becomes `stats::name`.
     In bindings/ the qualifier is `smi::stats::` / `smi::surrogate::`, because there `stats` and
     `surrogate` name the binding namespaces smi::bind::stats and smi::bind::surrogate.
     A name the file's own area (its folder's headers, or the file itself) declares is left alone:
     there it hides the stats name, so such uses were already qualified.

The stats symbol list is derived from host/kernels/stats/*.hpp: the names declared directly in its
namespace (old `smi` or new `smi::stats`), not in classes or detail. `--list` prints it.

Idempotent: every rewrite produces a form none of the patterns match again. It cannot be perfect
(a local lambda named like a stats function, a name hidden by a using-declaration): the compiler
finds the rest. Run: python3 tools/migrate/qualify_namespaces.py [repo root] [--list]
Prints each file changed.
"""
import os
import re
import sys

ARGS = [a for a in sys.argv[1:] if not a.startswith("--")]
ROOT = os.path.abspath(ARGS[0] if ARGS else os.path.join(os.path.dirname(__file__), "..", ".."))
EXTS = (".cpp", ".hpp", ".h", ".inc", ".cc", ".hh")
SKIP_DIRS = {".git", "build", "tmp", "tools"}
STATS_DIR = "host/kernels/stats/"
SURR_DIR = "host/kernels/surrogate/"
COMPONENTS = ["kriging", "doe", "delta", "polyfit", "propagate", "screen"]
AREA_OF = {c: "surrogate" for c in COMPONENTS}  # `using namespace smi::<x>` pulls in the names of area AREA_OF[x]
KEYWORDS = {
    "return", "else", "new", "delete", "throw", "case", "co_return", "co_await", "sizeof", "if", "while",
    "for", "switch", "operator", "const", "constexpr", "inline", "static", "explicit", "virtual", "typename",
    "template", "using", "namespace", "struct", "class", "enum", "union", "friend", "extern", "auto", "void",
    "decltype", "noexcept", "static_assert", "alignof", "default", "public", "private", "protected",
}
IDENT = r"[A-Za-z_]\w*"


def mask(text):
    """text with comments and string/char literals replaced by spaces (newlines kept), same length."""
    out = list(text)
    i, n = 0, len(text)

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(i, j)
            i = j
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
                                                              or text[i - 1] in "u8LU"):
            m = re.match(r'R"([^(\s]{0,16})\(', text[i:])
            if not m:
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            blank(i + 1, j)
            i = j
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):  # 1'000 digit separators
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            blank(i + 1, min(j, n))
            i = j + 1
        else:
            i += 1
    return "".join(out)


def top_level_names(masked, namespaces):
    """Names declared directly in one of `namespaces` (not inside classes or functions)."""
    funcs, others = set(), set()
    ns_open = re.compile(r"(?:^|[\s;}])namespace\s+([\w:]+)\s*\{$")
    depth, body_depths, stmt_start = 0, [], 0
    i, n = 0, len(masked)
    while i < n:
        c = masked[i]
        if c == "{":
            stmt = masked[stmt_start:i + 1]
            m = ns_open.search(stmt)
            in_body = body_depths and depth == body_depths[-1][0]
            if m and m.end() == len(stmt):
                body_depths.append((depth + 1, m.group(1) in namespaces))
            elif in_body and body_depths[-1][1]:
                classify(masked[stmt_start:i], funcs, others)
            depth += 1
            stmt_start = i + 1
        elif c == "}":
            depth -= 1
            if body_depths and depth < body_depths[-1][0]:
                body_depths.pop()
            stmt_start = i + 1
        elif c == ";":
            if body_depths and depth == body_depths[-1][0] and body_depths[-1][1]:
                classify(masked[stmt_start:i], funcs, others)
            if not body_depths or depth == body_depths[-1][0]:
                stmt_start = i + 1
        i += 1
    return funcs, others


def classify(stmt, funcs, others):
    stmt = re.sub(r"^\s*template\s*<[^;{]*?>\s*(?=[A-Za-z_])", "", stmt.strip())
    stmt = re.sub(r"\s+", " ", stmt)
    if not stmt or stmt.startswith(("using namespace", "static_assert", "#", "friend", "extern \"")):
        return
    m = re.match(r"(?:struct|class|union|enum(?: class| struct)?) (" + IDENT + r")\b", stmt)
    if m:
        others.add(m.group(1))
        return
    m = re.match(r"using (" + IDENT + r") =", stmt)
    if m:
        others.add(m.group(1))
        return
    # the first '(' outside <...>: a function declaration or definition
    angle = 0
    for k, ch in enumerate(stmt):
        if ch == "<":
            angle += 1
        elif ch == ">":
            angle = max(0, angle - 1)
        elif ch == "=" and angle == 0:
            break
        elif ch == "(" and angle == 0:
            m = re.search(r"(" + IDENT + r")\s*$", stmt[:k])
            if m and m.group(1) not in KEYWORDS and "operator" not in stmt[:k]:
                funcs.add(m.group(1))
            return
    m = re.search(r"(" + IDENT + r")\s*(?:\[[^\]]*\])?\s*(?:=.*|\{.*)?$", stmt)  # a variable or constant
    if m and m.group(1) not in KEYWORDS:
        others.add(m.group(1))


DECLARED = re.compile(r"\b\w[\w:<>]*[&*]?\s+[&*]?(" + IDENT + r")\s*\(|\b(" + IDENT + r")\s*=\s*\[|"
                      r"\b(?:struct|class|enum|using)\s+(?:class\s+)?(" + IDENT + r")")


def declared_names(masked):
    """Every name the text seems to declare (functions at any depth, lambdas, types)."""
    names = set()
    for m in DECLARED.finditer(masked):
        name = m.group(1) or m.group(2) or m.group(3)
        prev = masked[max(0, m.start() - 1):m.start() + 12].strip().split(" ")[0] if m.group(1) else ""
        if m.group(1) and re.match(r"(return|else|new|throw|case|co_return|delete)\b", masked[m.start():]):
            continue
        names.add(name)
    return names


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def sources(root):
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(filenames):
            if name.endswith(EXTS):
                full = os.path.join(dirpath, name)
                yield os.path.relpath(full, root).replace(os.sep, "/"), full


def stats_symbols(root):
    funcs, others = set(), set()
    d = os.path.join(root, STATS_DIR)
    for name in sorted(os.listdir(d)):
        if name.endswith(".hpp"):
            f, o = top_level_names(mask(read(os.path.join(d, name))), {"smi", "smi::stats"})
            funcs |= f
            others |= o
    return funcs - others, others


def group_of(rel):
    """The folder whose declarations share the file's namespace (a name there hides a stats name)."""
    m = re.match(r"(host/kernels/\w+|bindings/\w+|host/\w+)/", rel)
    return m.group(1) if m else None


def substitute(text, masked, pattern, repl):
    """re.sub on the code positions (matched in `masked`), applied to the original text."""
    out, last = [], 0
    for m in pattern.finditer(masked):
        r = repl(m)
        if r is None:
            continue
        out.append(text[last:m.start()])
        out.append(r)
        last = m.end()
    if not out:
        return text
    out.append(text[last:])
    return "".join(out)


def rewrite(rel, text, funcs, types, group_names, area_names):
    in_stats = rel.startswith(STATS_DIR)
    in_surr = rel.startswith(SURR_DIR)
    comps = "|".join(COMPONENTS)
    symbols = funcs | types
    sym_alt = "|".join(sorted(symbols, key=len, reverse=True))

    def step(pattern, repl):
        nonlocal text
        text = substitute(text, mask(text), re.compile(pattern), repl)

    # 1. namespace declarations of the moved files (and their closing comments)
    if in_stats:
        step(r"\bnamespace\s+smi\s*\{", lambda m: "namespace smi::stats {")
        step(r"\bnamespace\s+smi::detail\s*\{", lambda m: "namespace smi::stats::detail {")
        text = re.sub(r"(//\s*namespace\s+smi)(::detail)?[ \t]*$", lambda m: m.group(1) + "::stats" + (m.group(2) or ""),
                      text, flags=re.M)
    if in_surr:
        text = re.sub(r"(//\s*namespace\s+smi::)(" + comps + r")\b", r"\1surrogate::\2", text)
    # 2. fully qualified names
    step(r"(?<![\w:])smi::(" + comps + r")\b", lambda m: "smi::surrogate::" + m.group(1))
    # stats/parallel.hpp's and surrogate/parallel.hpp's loops (smi::detail) became core's pool (codecs)
    step(r"(?<![\w:])(?:smi::)?detail::parallel_(for|blocks)\b", lambda m: "smi::pool::parallel_" + m.group(1))
    step(r"(?<![\w:])smi::detail::", lambda m: "smi::stats::detail::")
    if sym_alt:
        step(r"(?<![\w:])smi::(" + sym_alt + r")\b(?!::)|(?<![\w:])smi::(" + sym_alt + r")(?=::)",
             lambda m: "smi::stats::" + (m.group(1) or m.group(2)))
    # 3. unqualified uses outside the moved area
    masked = mask(text)
    if not re.search(r"\bnamespace\s+smi\b|\busing\s+namespace\s+smi\b", masked):
        return text
    # `stats::` resolves where the file is inside namespace smi or pulls it in whole; in bindings
    # and in files that only pull in smi::<something> the qualifier starts at smi::
    short = re.search(r"\bnamespace\s+smi\b|\busing\s+namespace\s+smi\s*;", masked) and not rel.startswith("bindings/")
    stats_q = "stats::" if short else "smi::stats::"
    surr_q = "surrogate::" if short else "smi::surrogate::"
    if not in_surr:
        step(r"(?<![\w:.>])(" + comps + r")::", lambda m: surr_q + m.group(1) + "::")
    if not in_stats and sym_alt:
        own = declared_names(masked) | group_names
        for m in re.finditer(r"\busing\s+namespace\s+smi::(\w+)", masked):  # e.g. smi::kriging: its fit()
            own |= area_names.get(AREA_OF.get(m.group(1), m.group(1)), set())

        def qualify(m):
            name = m.group(1)
            if name in own:
                return None
            after = text_after(m)
            if name in funcs and name not in types and not re.match(r"\s*[(<]", after):
                return None
            before = masked[max(0, m.start() - 40):m.start()]
            if re.search(r"\b(?:struct|class|enum|union|namespace|goto)\s+$|~\s*$", before):
                return None
            return stats_q + name

        cur = {"text": None}

        def text_after(m):
            return cur["text"][m.end():m.end() + 8]

        cur["text"] = mask(text)
        step(r"(?<![\w:.>~#])(?<!->)(" + sym_alt + r")\b", qualify)
    return text


def main():
    funcs, types = stats_symbols(ROOT)
    if "--list" in sys.argv:
        print("functions:", " ".join(sorted(funcs)))
        print("types and constants:", " ".join(sorted(types)))
        return
    files = list(sources(ROOT))
    group_cache = {}
    for rel, full in files:
        g = group_of(rel)
        if g and g not in group_cache:
            names = set()
            for rel2, full2 in files:
                if group_of(rel2) == g and rel2.endswith((".hpp", ".h")):
                    names |= declared_names(mask(read(full2)))
            group_cache[g] = names
    area_names = {a: group_cache.get("host/kernels/" + a, set()) for a in ("surrogate", "improve", "eval")}
    for rel, full in files:
        text = read(full)
        new = rewrite(rel, text, funcs, types, group_cache.get(group_of(rel), set()), area_names)
        if new != text:
            with open(full, "w", encoding="utf-8") as f:
                f.write(new)
            print(rel)


if __name__ == "__main__":
    main()
