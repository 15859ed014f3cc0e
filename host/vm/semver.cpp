// SPDX-License-Identifier: MIT
#include "vm/semver.hpp"

#include <cctype>

#include "platform/core/errors.hpp"

namespace smi::vm {
namespace {

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = s.find(sep, start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

long number_part(const std::string& part, const std::string& whole, const char* which) {
  if (!all_digits(part) || part.size() > 9)
    throw Error("version '" + whole + "': the " + which + " part '" + part +
                "' is not a whole number (write versions as MAJOR.MINOR.PATCH, e.g. 1.2.0)");
  if (part.size() > 1 && part[0] == '0')
    throw Error("version '" + whole + "': the " + which + " part '" + part + "' has a leading zero");
  return std::stol(part);
}

/// Semver's dot-separated identifiers of a prerelease or build metadata: each non-empty,
/// of [0-9A-Za-z-] only.
std::vector<std::string> identifiers(const std::string& text, const std::string& whole, const char* what) {
  std::vector<std::string> ids = split(text, '.');
  for (const std::string& id : ids) {
    if (id.empty()) throw Error("version '" + whole + "': empty " + what + " identifier (write e.g. 1.2.0-rc.1+build.5)");
    for (char c : id)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-')
        throw Error("version '" + whole + "': " + what + " identifiers use only [0-9A-Za-z-], separated by dots");
  }
  return ids;
}

Version parse_impl(const std::string& s, bool loose) {
  Version v;
  v.text = s;
  std::string core = s;
  if (const std::size_t plus = core.find('+'); plus != std::string::npos) {
    // Build metadata is data like the rest of the version: a version names a folder of the
    // library tree, so a '/' or a ".." here would be a path.
    identifiers(core.substr(plus + 1), s, "build metadata");
    core = core.substr(0, plus);
  }
  if (const std::size_t dash = core.find('-'); dash != std::string::npos) {
    const std::string pre = core.substr(dash + 1);
    core = core.substr(0, dash);
    v.pre = identifiers(pre, s, "prerelease");
  }
  const std::vector<std::string> parts = split(core, '.');
  if (parts.size() != 3 && !(loose && parts.size() < 3))
    throw Error("version '" + s + "' is not MAJOR.MINOR.PATCH (write e.g. \"1.2.0\")");
  static const char* const kWhich[] = {"major", "minor", "patch"};
  long* fields[] = {&v.major, &v.minor, &v.patch};
  for (std::size_t i = 0; i < parts.size(); ++i) *fields[i] = number_part(parts[i], s, kWhich[i]);
  return v;
}

}  // namespace

Version Version::parse(const std::string& s) { return parse_impl(s, false); }
Version Version::parse_loose(const std::string& s) { return parse_impl(s, true); }

int compare(const Version& a, const Version& b) {
  if (a.major != b.major) return a.major < b.major ? -1 : 1;
  if (a.minor != b.minor) return a.minor < b.minor ? -1 : 1;
  if (a.patch != b.patch) return a.patch < b.patch ? -1 : 1;
  if (a.pre.empty() || b.pre.empty()) return a.pre.empty() == b.pre.empty() ? 0 : (a.pre.empty() ? 1 : -1);
  for (std::size_t i = 0; i < a.pre.size() && i < b.pre.size(); ++i) {
    const std::string &x = a.pre[i], &y = b.pre[i];
    const bool nx = all_digits(x), ny = all_digits(y);
    if (nx && ny) {
      if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;  // no leading zeros: longer is larger
      if (x != y) return x < y ? -1 : 1;
    } else if (nx != ny) {
      return nx ? -1 : 1;  // numeric identifiers sort before alphanumeric ones
    } else if (x != y) {
      return x < y ? -1 : 1;
    }
  }
  if (a.pre.size() != b.pre.size()) return a.pre.size() < b.pre.size() ? -1 : 1;
  return 0;
}

Requirement Requirement::parse(const std::string& s) {
  Requirement r;
  r.text = s;
  const std::string t = trim(s);
  std::size_t i = 0;
  while (i < t.size() && (std::isalnum(static_cast<unsigned char>(t[i])) || t[i] == '_' || t[i] == '-')) ++i;
  r.name = t.substr(0, i);
  const auto bad = [&](const std::string& why) {
    return Error("requirement '" + s + "': " + why +
                 " (write \"name\", \"name >= 1.2\", \"name >= 1.2, < 2\" or \"name ^1.2\")");
  };
  if (r.name.empty()) throw bad("it does not start with a library name");
  const std::string rest = trim(t.substr(i));
  if (rest.empty()) return r;
  for (const std::string& piece : split(rest, ',')) {
    const std::string p = trim(piece);
    std::size_t k = 0;
    while (k < p.size() && std::string("<>=!^~").find(p[k]) != std::string::npos) ++k;
    Bound b;
    b.op = p.substr(0, k);
    if (b.op == "=") b.op = "==";
    if (b.op == "~=") b.op = "!=";
    static const char* const kOps[] = {">=", ">", "<=", "<", "==", "!=", "^"};
    bool known = false;
    for (const char* op : kOps) known = known || b.op == op;
    if (!known) throw bad(b.op.empty() ? "'" + p + "' has no comparison operator" : "unknown operator '" + b.op + "'");
    const std::string ver = trim(p.substr(k));
    try {
      b.v = Version::parse_loose(ver);
    } catch (const Error& e) {
      throw bad(e.what());
    }
    r.bounds.push_back(b);
  }
  return r;
}

bool Requirement::accepts(const Version& v) const {
  for (const Bound& b : bounds) {
    const int c = compare(v, b.v);
    bool ok = true;
    if (b.op == ">=") ok = c >= 0;
    else if (b.op == ">") ok = c > 0;
    else if (b.op == "<=") ok = c <= 0;
    else if (b.op == "<") ok = c < 0;
    else if (b.op == "==") ok = c == 0;
    else if (b.op == "!=") ok = c != 0;
    else if (b.op == "^") ok = c >= 0 && v.major == b.v.major;
    if (!ok) return false;
  }
  return true;
}

std::string Requirement::constraint() const {
  if (bounds.empty()) return "any version";
  std::string s;
  for (const Bound& b : bounds) s += (s.empty() ? "" : ", ") + b.op + (b.op == "^" ? "" : " ") + b.v.text;
  return s;
}

}  // namespace smi::vm
