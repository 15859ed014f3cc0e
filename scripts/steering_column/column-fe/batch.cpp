// SPDX-License-Identifier: MIT
#include "batch.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <sstream>
#include <thread>

#include "deck.hpp"
#include "solve.hpp"

namespace cfe {
namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

[[noreturn]] void fail(const std::string& file, int row, const std::string& col, const std::string& value,
                       const std::string& why) {
  throw DeckError(file + ": row " + std::to_string(row) + ", column '" + col + "', value '" + value + "': " + why);
}

}  // namespace

BatchPoints parse_points(const std::string& text, const std::string& file) {
  BatchPoints p;
  std::istringstream is(text);
  std::string line;
  int lineno = 0;
  bool header = false;
  while (std::getline(is, line)) {
    ++lineno;
    const std::string body = trim(line);
    if (body.empty() || body[0] == '#') continue;
    const auto cells = split(body);
    if (!header) {
      for (const auto& c : cells) {
        const std::string name = c.size() >= 2 && c.front() == '"' && c.back() == '"' ? c.substr(1, c.size() - 2) : c;
        if (!find_input(name))
          throw DeckError(file + ": header names '" + name + "', which is not an input (use the names of spec section 2, "
                          "e.g. column_frame_E, or airbag_stiffness)");
        for (const auto& seen : p.names)
          if (seen == name) throw DeckError(file + ": header names '" + name + "' twice; give each input once");
        p.names.push_back(name);
      }
      header = true;
      continue;
    }
    const int row = static_cast<int>(p.rows.size()) + 1;
    if (cells.size() != p.names.size())
      throw DeckError(file + ": line " + std::to_string(lineno) + " (row " + std::to_string(row) + ") has " +
                      std::to_string(cells.size()) + " values but the header names " + std::to_string(p.names.size()) +
                      " inputs");
    std::vector<double> v(cells.size());
    for (std::size_t j = 0; j < cells.size(); ++j) {
      char* end = nullptr;
      v[j] = std::strtod(cells[j].c_str(), &end);
      if (cells[j].empty() || end == nullptr || *end != '\0') fail(file, row, p.names[j], cells[j], "not a number");
    }
    p.rows.push_back(std::move(v));
  }
  if (!header) throw DeckError(file + ": empty; expected a header of input names and one row per point");
  return p;
}

Inputs point_inputs(const Inputs& base, const BatchPoints& pts, std::size_t i, const std::string& file) {
  Inputs in = base;
  const int row = static_cast<int>(i) + 1;
  for (std::size_t j = 0; j < pts.names.size(); ++j) {
    const double x = pts.rows[i][j];
    const std::string& name = pts.names[j];
    char text[64];
    for (int digits = 6; digits <= 17; ++digits) {  // the shortest text that reads back as x
      std::snprintf(text, sizeof text, "%.*g", digits, x);
      if (std::strtod(text, nullptr) == x) break;
    }
    if (!std::isfinite(x)) fail(file, row, name, text, "not finite");
    if (find_input(name)->kind == InputKind::poisson && !(x > 0 && x < 0.5))
      fail(file, row, name, text, "a Poisson's ratio must lie in (0, 0.5)");
    if (x <= 0) fail(file, row, name, text, "must be > 0");
    if (name == "airbag_stiffness" && in.airbag == Airbag::rigid) continue;  // ignored for rigid (§9)
    in.values[name] = x;
  }
  return in;
}

void run_batch(const Inputs& base, const BatchPoints& pts, const std::string& file, std::ostream& os, int threads) {
  const std::size_t n = pts.rows.size();
  std::vector<Inputs> inputs;
  inputs.reserve(n);
  for (std::size_t i = 0; i < n; ++i) inputs.push_back(point_inputs(base, pts, i, file));  // all checked first
  std::vector<std::array<double, 4>> hz(n);
  std::vector<std::string> errors(n);
  auto work = [&](std::size_t first, std::size_t step) {
    for (std::size_t i = first; i < n; i += step) {
      try {
        hz[i] = run_model(inputs[i]).paper_hz;
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
    }
  };
  const auto t = static_cast<std::size_t>(threads < 1 ? 1 : threads);
  if (t == 1 || n < 2) {
    work(0, 1);
  } else {
    std::vector<std::thread> pool;
    for (std::size_t k = 0; k < t; ++k) pool.emplace_back(work, k, t);
    for (auto& th : pool) th.join();
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!errors[i].empty()) throw std::runtime_error(file + ": row " + std::to_string(i + 1) + ": " + errors[i]);
  os << "point,mode1_hz,mode2_hz,mode3_hz,mode4_hz\n";
  char line[160];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%zu,%.10g,%.10g,%.10g,%.10g\n", i + 1, hz[i][0], hz[i][1], hz[i][2], hz[i][3]);
    os << line;
  }
}

}  // namespace cfe
