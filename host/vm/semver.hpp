// SPDX-License-Identifier: MIT
#pragma once
// Library versions (Semantic Versioning 2.0.0: MAJOR.MINOR.PATCH[-prerelease][+build]) and the
// requirements manifests state on each other ("stats_extra >= 1.2, < 2").
#include <optional>
#include <string>
#include <vector>

namespace smi::vm {

struct Version {
  long major = 0, minor = 0, patch = 0;
  std::vector<std::string> pre;  // prerelease identifiers ("rc", "1"); empty for a release
  std::string text;              // as written

  /// Strict: "1.2.0", "1.2.0-rc.1", "1.2.0+build.5". Throws smi::Error saying what is wrong.
  static Version parse(const std::string& s);
  /// Lenient, for requirements: "1", "1.2" mean "1.0.0", "1.2.0".
  static Version parse_loose(const std::string& s);
};

/// <0, 0, >0 by semver precedence (build metadata ignored; a prerelease sorts before its release).
int compare(const Version& a, const Version& b);

/// One "name op version, op version" requirement. Operators: >= > <= < == = != and ^ (same
/// major, at least the version: "^1.2" is ">= 1.2, < 2"); a bare name accepts any version.
struct Requirement {
  struct Bound {
    std::string op;
    Version v;
  };
  std::string name;
  std::vector<Bound> bounds;
  std::string text;  // as written

  /// Throws smi::Error naming the requirement and the expected form.
  static Requirement parse(const std::string& s);
  bool accepts(const Version& v) const;
  /// The constraint part alone (">= 1.2, < 2"), or "any version".
  std::string constraint() const;
};

}  // namespace smi::vm
