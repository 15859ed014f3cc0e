// SPDX-License-Identifier: MIT
// The sandbox's path resolver (platform/core/path_walk.hpp), one case per branch of walk()'s
// state machine, from a table. Each case walks a path in a fixed tree made in a fresh temporary
// folder and checks the error, the canonical folder and leaf, and whether the leaf exists; where
// the kernel can answer too (realpath(3), stat(2), lstat(2)), the walk must agree with it: the
// canonical path names the same object (device and inode) the kernel reaches by the same path.
// bench/fuzz_path_walk.cpp fuzzes the same property on random paths; this is its table in CI.
#include <catch2/catch.hpp>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "platform/core/path_walk.hpp"

namespace fs = std::filesystem;
using smi::pathwalk::walk;

namespace {

/// The tree every case walks: root/{a/{f, b/{g, c/}}, d/, links...} and outside/secret beside it.
struct Tree {
  std::string base, root;
  Tree() {
    char tmpl[] = "/tmp/test_path_walk.XXXXXX";
    const char* made = ::mkdtemp(tmpl);
    REQUIRE(made != nullptr);
    base = fs::canonical(made).string();
    root = base + "/root";
    fs::create_directories(root + "/a/b/c");
    fs::create_directories(root + "/d");
    fs::create_directories(base + "/outside");
    write(root + "/a/f");
    write(root + "/a/b/g");
    write(base + "/outside/secret");
    link("a/b", "la");                          // relative, inside
    link("../outside", "lo");                    // relative, leads out
    link(base + "/outside/secret", "ls");        // absolute, to a file outside
    link("missing", "dang");                     // dangling
    link("loop2", "loop1");                      // a loop of two
    link("loop1", "loop2");
    link("a/", "lslash");                        // target ends in "/": names a folder
    link("a/f", "lf");                           // to a file, used as a folder below
    for (int i = 0; i < 41; ++i)                 // a chain of 41 links: one more than the kernel allows
      link(i == 40 ? std::string("a") : "chain" + std::to_string(i + 1), "chain" + std::to_string(i));
  }
  ~Tree() {
    std::error_code ec;
    fs::remove_all(base, ec);
  }
  static void write(const std::string& p) {
    const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    REQUIRE(fd >= 0);
    REQUIRE(smi::pathwalk::write_all(fd, "x\n"));
    ::close(fd);
  }
  void link(const std::string& target, const std::string& name) const {
    REQUIRE(::symlink(target.c_str(), (root + "/" + name).c_str()) == 0);
  }
};

struct Case {
  const char* path;       // relative to root unless it starts with '/' or "@" (= base)
  bool follow_last;
  int error;              // expected errno, 0 for none
  const char* canonical;  // expected canonical path ("@" = base), when error == 0
  bool exists;
  const char* branch;     // the branch of walk() the case exercises
};

std::string expand(const std::string& s, const Tree& t) {
  if (!s.empty() && s[0] == '@') return t.base + s.substr(1);
  if (!s.empty() && s[0] == '/') return s;
  return t.root + "/" + s;
}

bool same_object(const std::string& a, const std::string& b, bool follow) {
  struct stat sa, sb;
  const int ra = follow ? ::stat(a.c_str(), &sa) : ::lstat(a.c_str(), &sa);
  const int rb = follow ? ::stat(b.c_str(), &sb) : ::lstat(b.c_str(), &sb);
  return ra == 0 && rb == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace

TEST_CASE("walk: each branch of the state machine, against the kernel where it can answer") {
  Tree t;
  const std::vector<Case> cases = {
      {"a/f", true, 0, "@/root/a/f", true, "plain descent to a file"},
      {"a/b", true, 0, "@/root/a/b", true, "a folder as last component: (parent, name)"},
      {"/", true, 0, "/", true, "the root itself: no leaf"},
      {"a/./b/./g", true, 0, "@/root/a/b/g", true, "'.' is skipped"},
      {"a/b/../f", true, 0, "@/root/a/f", true, "'..' goes back one held folder"},
      {"/../../..", true, 0, "/", true, "'..' at the root stays at the root"},
      {"a/new", true, 0, "@/root/a/new", false, "missing last component: no error, exists = false"},
      {"a/new", false, 0, "@/root/a/new", false, "missing last component, not followed"},
      {"a/nope/x", true, ENOENT, nullptr, false, "missing folder before the last component"},
      {"a/f/x", true, ENOTDIR, nullptr, false, "a file where a folder is needed"},
      {"a/f/", true, ENOTDIR, nullptr, false, "trailing '/' on a file"},
      {"a/b/", true, 0, "@/root/a/b", true, "trailing '/' on a folder"},
      {"la/g", true, 0, "@/root/a/b/g", true, "relative link spliced into the queue"},
      {"la/../f", true, 0, "@/root/a/f", true, "'..' after a link: the target's parent (as the kernel)"},
      {"lo/secret", true, 0, "@/outside/secret", true, "link leading out: the canonical path says so"},
      {"ls", true, 0, "@/outside/secret", true, "absolute link as last, followed: the walk restarts at /"},
      {"ls", false, 0, "@/root/ls", true, "link as last, not followed: the link itself"},
      {"dang", true, 0, "@/root/missing", false, "dangling link followed: its missing target"},
      {"dang", false, 0, "@/root/dang", true, "dangling link not followed: the link exists"},
      {"loop1", true, ELOOP, nullptr, false, "a loop of links"},
      {"loop1", false, 0, "@/root/loop1", true, "a loop not followed: the link itself"},
      {"loop1/x", true, ELOOP, nullptr, false, "a loop in the middle"},
      {"chain1/f", true, 0, "@/root/a/f", true, "40 links in a row: the kernel's limit, allowed"},
      {"chain0/f", true, ELOOP, nullptr, false, "41 links in a row: over the limit"},
      {"lslash", false, 0, "@/root/lslash", true, "link whose target ends in '/', not followed"},
      {"lslash", true, 0, "@/root/a", true, "link whose target ends in '/', followed: a folder"},
      {"lf/", true, ENOTDIR, nullptr, false, "'link/' follows the link; a file is no folder"},
      {"lf/x", true, ENOTDIR, nullptr, false, "a link to a file used as a folder"},
  };
  for (const auto& c : cases) {
    INFO(c.branch << ": walk(\"" << c.path << "\", follow_last = " << c.follow_last << ")");
    const std::string path = expand(c.path, t);
    const auto w = walk(path, c.follow_last);
    CHECK(w.error == c.error);
    if (c.error != 0) {
      CHECK(!w.where.empty());  // messages name where the walk stopped
      continue;
    }
    CHECK(w.canonical() == expand(c.canonical, t));
    CHECK(w.exists == c.exists);
    CHECK(w.dir);
    CHECK(w.leaf != "." );
    CHECK(w.leaf != "..");
    if (w.exists) {
      // The kernel's view: the same object by the given path and by the canonical one.
      CHECK(same_object(path, w.canonical(), c.follow_last));
      // The folder descriptor is the canonical folder.
      struct stat sd, sp;
      REQUIRE(::fstat(w.dir.get(), &sd) == 0);
      REQUIRE(::stat(w.dir_path.c_str(), &sp) == 0);
      CHECK((sd.st_dev == sp.st_dev && sd.st_ino == sp.st_ino));
      if (c.follow_last) {
        char real[PATH_MAX];
        REQUIRE(::realpath(path.c_str(), real) != nullptr);
        CHECK(w.canonical() == real);
      }
    }
  }
}

TEST_CASE("walk: a relative path starts at the working folder's canonical path") {
  Tree t;
  const fs::path old = fs::current_path();
  fs::current_path(t.root + "/la");  // through the link: cwd is the canonical a/b
  const auto w = walk("../f", true);
  fs::current_path(old);
  CHECK(w.error == 0);
  CHECK(w.canonical() == t.root + "/a/f");
}

TEST_CASE("walk: the path text is refused before any component when it cannot be walked") {
  CHECK(walk("", true).error == ENOENT);
  CHECK(walk(std::string("/tmp/a\0b", 8), true).error == EINVAL);        // a NUL would cut the kernel's name
  CHECK(walk(std::string(64 * 1024 + 1, 'a'), true).error == ENAMETOOLONG);  // over 64 KiB of text
  std::string many;
  for (int i = 0; i < 4097; ++i) many += "/.";
  CHECK(walk(many, true).error == ENAMETOOLONG);                         // over 4096 components
  CHECK(walk("/" + std::string(NAME_MAX + 1, 'n'), true).error == ENAMETOOLONG);  // one name too long
}

TEST_CASE("walk: more than 128 folders deep is refused") {
  Tree t;
  std::string deep = t.root + "/d";
  std::string rel;
  for (int i = 0; i < 130; ++i) rel += "/x";
  fs::create_directories(deep + rel);
  const auto w = walk(deep + rel + "/leaf", true);
  CHECK(w.error == ENAMETOOLONG);
}

TEST_CASE("within: a path is within a root only at a component boundary") {
  CHECK(smi::pathwalk::within("/a/b", "/a"));
  CHECK(smi::pathwalk::within("/a", "/a"));
  CHECK(smi::pathwalk::within("/a/b", "/a/"));
  CHECK_FALSE(smi::pathwalk::within("/a/bc", "/a/b"));
  CHECK_FALSE(smi::pathwalk::within("/a", "/a/b"));
  CHECK(smi::pathwalk::within("/anything", "/"));
  CHECK_FALSE(smi::pathwalk::within("/a", ""));
  CHECK_FALSE(smi::pathwalk::within("relative", "/"));
}

TEST_CASE("make_dirs_nofollow creates folders and refuses links and dot components") {
  Tree t;
  {
    const auto fd = smi::pathwalk::make_dirs_nofollow(t.root + "/d/n1/n2");
    CHECK(fd);
    CHECK(fs::is_directory(t.root + "/d/n1/n2"));
  }
  errno = 0;
  CHECK_FALSE(smi::pathwalk::make_dirs_nofollow(t.root + "/la/new"));  // la is a link
  CHECK(errno == ENOTDIR);
  CHECK_FALSE(fs::exists(t.root + "/a/b/new"));
  errno = 0;
  CHECK_FALSE(smi::pathwalk::make_dirs_nofollow(t.root + "/d/../x"));
  CHECK(errno == EINVAL);
}

TEST_CASE("remove_tree_at removes a folder's contents and never follows a link") {
  Tree t;
  fs::create_directories(t.root + "/d/tree/sub");
  Tree::write(t.root + "/d/tree/sub/file");
  REQUIRE(::symlink((t.base + "/outside").c_str(), (t.root + "/d/tree/out").c_str()) == 0);
  const int dfd = ::open((t.root + "/d").c_str(), O_RDONLY | O_DIRECTORY);
  REQUIRE(dfd >= 0);
  CHECK(smi::pathwalk::remove_tree_at(dfd, "tree"));
  CHECK(smi::pathwalk::remove_tree_at(dfd, "tree"));  // missing is success
  ::close(dfd);
  CHECK_FALSE(fs::exists(t.root + "/d/tree"));
  CHECK(fs::exists(t.base + "/outside/secret"));  // the link's target is untouched
}

TEST_CASE("read_all stops at its limit with EFBIG") {
  Tree t;
  const int fd = ::open((t.root + "/a/f").c_str(), O_RDONLY);
  REQUIRE(fd >= 0);
  std::string out;
  errno = 0;
  CHECK_FALSE(smi::pathwalk::read_all(fd, out, 1));
  CHECK(errno == EFBIG);
  REQUIRE(::lseek(fd, 0, SEEK_SET) == 0);
  CHECK(smi::pathwalk::read_all(fd, out));
  CHECK(out == "x\n");
  ::close(fd);
}
