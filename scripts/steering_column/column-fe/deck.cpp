// SPDX-License-Identifier: MIT
#include "deck.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <algorithm>
#include <map>
#include <vector>
#include <sstream>

namespace cfe {

namespace {

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

[[noreturn]] void fail_at(const std::string& file, int line, const std::string& key, const std::string& value,
                       const std::string& what) {
  std::ostringstream os;
  os << file << ":" << line << ": key '" << key << "' value '" << value << "': " << what;
  throw DeckError(os.str());
}

// strtod accepts "1e-9", "inf", "nan" and hex; we want the whole token to be a number.
bool to_number(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  x = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// Levenshtein distance, to suggest the key a typo most likely meant.
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string suggestion(const std::string& key) {
  std::string best = "airbag_model";
  std::size_t d = distance(key, best);
  for (const std::string& k : {std::string("mesh_refinement")})
    if (distance(key, k) < d) d = distance(key, best = k);
  for (const auto& s : input_specs())
    if (distance(key, s.name) < d) d = distance(key, best = s.name);
  return d <= 3 ? "did you mean '" + best + "'? " : "";
}

}  // namespace

Inputs parse_deck(const std::string& text, const std::string& file) {
  Inputs in;
  std::map<std::string, int> seen;  // key -> line of first appearance
  std::istringstream is(text);
  std::string raw;
  int line = 0;
  bool have_model = false;
  while (std::getline(is, raw)) {
    ++line;
    const std::string body = trimmed(raw.substr(0, raw.find('#')));
    if (body.empty()) continue;
    const auto eq = body.find('=');
    if (eq == std::string::npos)
      fail_at(file, line, body, "", "expected 'key = value' (a '#' starts a comment)");
    const std::string key = trimmed(body.substr(0, eq)), value = trimmed(body.substr(eq + 1));
    if (key.empty()) fail_at(file, line, key, value, "missing key before '='");
    if (auto [it, fresh] = seen.emplace(key, line); !fresh)
      fail_at(file, line, key, value, "duplicate key (first given on line " + std::to_string(it->second) + "); give each key once");
    if (key == "airbag_model") {
      if (value == "rigid") in.airbag = Airbag::rigid;
      else if (value == "spring") in.airbag = Airbag::spring;
      else fail_at(file, line, key, value, "must be 'rigid' or 'spring'");
      have_model = true;
      continue;
    }
    double x = 0;
    if (key == "mesh_refinement") {
      if (!to_number(value, x) || x != std::floor(x) || x < 1 || x > 8)
        fail_at(file, line, key, value, "must be an integer from 1 to 8");
      in.refinement = static_cast<int>(x);
      continue;
    }
    const InputSpec* spec = find_input(key);
    if (!spec)
      fail_at(file, line, key, value,
           "unknown key; " + suggestion(key) + "expected airbag_model, mesh_refinement, airbag_stiffness or one of the 46 inputs "
           "(column_frame_E, ..., tilt_lock_k; spec steering-column.md section 2)");
    if (!to_number(value, x)) fail_at(file, line, key, value, "not a number");
    if (!std::isfinite(x)) fail_at(file, line, key, value, "not finite");
    if (spec->kind == InputKind::poisson && !(x > 0 && x < 0.5))
      fail_at(file, line, key, value, "a Poisson's ratio must lie in (0, 0.5)");
    if (x <= 0) fail_at(file, line, key, value, "must be > 0");
    in.values[key] = x;
  }
  std::string missing;
  if (!have_model) missing += " airbag_model";
  for (const auto& s : input_specs()) {
    if (s.name == "airbag_stiffness" && in.airbag == Airbag::rigid) continue;
    if (!in.values.count(s.name)) missing += " " + s.name;
  }
  if (!missing.empty()) throw DeckError(file + ": missing required key(s):" + missing + "; add a 'key = value' line for each");
  if (in.airbag == Airbag::rigid) in.values.erase("airbag_stiffness");  // ignored for rigid (§9)
  return in;
}

Inputs read_deck(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw DeckError(path + ": cannot open the deck file (check the path and permissions)");
  std::ostringstream ss;
  ss << f.rdbuf();
  return parse_deck(ss.str(), path);
}

std::string write_deck(const Inputs& in) {
  std::ostringstream os;
  os << "# steering column analog: input deck\n"
     << "# units: N, mm, tonne, s (modulus MPa, density tonne/mm^3, stiffness N/mm)\n"
     << "airbag_model = " << airbag_name(in.airbag) << "\n";
  if (in.refinement != 1) os << "mesh_refinement = " << in.refinement << "\n";
  char buf[64];
  for (const auto& s : input_specs()) {
    if (s.name == "airbag_stiffness" && in.airbag == Airbag::rigid) continue;
    std::snprintf(buf, sizeof buf, "%.17g", in(s.name));
    os << s.name << " = " << buf << "\n";
  }
  return os.str();
}

}  // namespace cfe
