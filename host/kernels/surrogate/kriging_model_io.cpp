// SPDX-License-Identifier: MIT
// Kriging model files: a small self-describing text format. We store what defines the model
// (data, scalings, trend, correlation, theta, nugget) and refactorise on load, which gives
// the same numbers bit for bit (same operations in the same order).
//   smi-kriging 1
//   trend constant / corr gauss / nugget <x> / method ml / evaluations <k>
//   inputs <n> / points <m>
//   theta ... / mS ... / sS ... / mY <x> / sY <x>
//   S (m lines of n numbers) / Y (m numbers)
//   (version 2) names <k> then k lines of one input name each (k = 0 or n) / output <name>
//   end
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "kernels/surrogate/kriging.hpp"
#include "kernels/surrogate/likelihood.hpp"
#include "platform/core/errors.hpp"

namespace smi::surrogate::kriging {
namespace {

void put(std::ostream& os, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, " %.17g", v);
  os << buf;
}

struct Reader {
  std::istream& is;
  std::string path;
  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidArgument("kriging model file '" + path + "': " + what);
  }
  void expect(const std::string& key) {
    std::string k;
    if (!(is >> k) || k != key) fail("expected '" + key + "', found '" + k + "'");
  }
  std::string word(const std::string& key) {
    expect(key);
    std::string v;
    if (!(is >> v)) fail("missing value of '" + key + "'");
    return v;
  }
  double number() {
    std::string s;
    if (!(is >> s)) fail("truncated file");
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end) fail("'" + s + "' is not a number");
    return v;
  }
  long count(const std::string& key) {
    expect(key);
    const double v = number();
    if (!(v >= 0 && v < 1e8 && v == std::floor(v))) fail("bad count for '" + key + "'");
    return static_cast<long>(v);
  }
};

}  // namespace

void save(const Model& md, std::ostream& os, const std::string& path, const ModelNames& names) {
  if (md.S.size() == 0) throw InvalidArgument("cannot save an empty model");
  if (!names.inputs.empty() && static_cast<Eigen::Index>(names.inputs.size()) != md.inputs())
    throw InvalidArgument("cannot save " + std::to_string(names.inputs.size()) + " input names for a model of " +
                          std::to_string(md.inputs()) + " inputs");
  auto check_name = [](const std::string& s) {  // one name per line: a line break would split it
    if (s.find_first_of("\r\n") != std::string::npos || s.empty())
      throw InvalidArgument("cannot save the name '" + s + "': names must be non-empty and on one line");
  };
  for (const auto& s : names.inputs) check_name(s);
  if (!names.output.empty()) check_name(names.output);
  const Eigen::Index m = md.size(), n = md.inputs();
  os << "smi-kriging 2\ntrend " << trend_name(md.trend) << "\ncorr " << corr_name(md.corr) << "\nmethod "
     << md.method << "\nevaluations " << md.evaluations << "\nnugget";
  put(os, md.nugget);
  os << "\ninputs " << n << "\npoints " << m << "\ntheta";
  for (Eigen::Index j = 0; j < n; ++j) put(os, md.theta[j]);
  os << "\nmS";
  for (Eigen::Index j = 0; j < n; ++j) put(os, md.mS[j]);
  os << "\nsS";
  for (Eigen::Index j = 0; j < n; ++j) put(os, md.sS[j]);
  os << "\nmY";
  put(os, md.mY);
  os << "\nsY";
  put(os, md.sY);
  os << "\nS\n";
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) put(os, md.S(i, j));
    os << "\n";
  }
  os << "Y\n";
  for (Eigen::Index i = 0; i < m; ++i) {
    put(os, md.Y[i]);
    os << "\n";
  }
  os << "names " << names.inputs.size() << "\n";
  for (const auto& s : names.inputs) os << s << "\n";
  os << "output " << (names.output.empty() ? "y" : names.output) << "\nend\n";
  if (!os) throw InvalidArgument("writing '" + path + "' failed");
}

void save(const Model& md, const std::string& path, const ModelNames& names) {
  std::ostringstream text;
  save(md, text, path, names);  // checks and renders before the file is touched
  std::ofstream os(path);
  if (!os) throw InvalidArgument("cannot open '" + path + "' for writing");
  os << text.str();
  if (!os) throw InvalidArgument("writing '" + path + "' failed");
}

Model load(const std::string& path, ModelNames* names) {
  std::ifstream is(path);
  if (!is) throw InvalidArgument("cannot open '" + path + "'");
  return load(is, path, names);
}

Model load(std::istream& is, const std::string& path, ModelNames* names) {
  Reader rd{is, path};
  std::string magic, version;
  is >> magic >> version;
  if (magic != "smi-kriging") rd.fail("not a Kriging model file (no 'smi-kriging' header)");
  if (version != "1" && version != "2") rd.fail("unsupported version " + version + " (this smi-lua reads 1 and 2)");
  Model md;
  md.trend = parse_trend(rd.word("trend"));
  md.corr = parse_corr(rd.word("corr"));
  md.method = rd.word("method");
  rd.expect("evaluations");
  md.evaluations = static_cast<int>(rd.number());
  rd.expect("nugget");
  md.nugget = rd.number();
  const long n = rd.count("inputs"), m = rd.count("points");
  if (n < 1 || m < 2) rd.fail("needs at least 1 input and 2 points");
  auto row = [&](const char* key) {
    rd.expect(key);
    Eigen::VectorXd v(n);
    for (long j = 0; j < n; ++j) v[j] = rd.number();
    return v;
  };
  md.theta = row("theta");
  md.mS = row("mS").transpose();
  md.sS = row("sS").transpose();
  rd.expect("mY");
  md.mY = rd.number();
  rd.expect("sY");
  md.sY = rd.number();
  rd.expect("S");
  md.S.resize(m, n);
  for (long i = 0; i < m; ++i)
    for (long j = 0; j < n; ++j) md.S(i, j) = rd.number();
  rd.expect("Y");
  md.Y.resize(m);
  for (long i = 0; i < m; ++i) md.Y[i] = rd.number();
  ModelNames nm;
  if (version == "2") {
    const long k = rd.count("names");
    if (k != 0 && k != n) rd.fail(std::to_string(k) + " input names for " + std::to_string(n) + " inputs");
    std::string line;
    std::getline(is, line);  // the rest of the 'names' line
    for (long j = 0; j < k; ++j) {
      if (!std::getline(is, line) || line.empty()) rd.fail("missing input name " + std::to_string(j + 1));
      nm.inputs.push_back(line);
    }
    rd.expect("output");
    is >> std::ws;
    if (!std::getline(is, nm.output) || nm.output.empty()) rd.fail("missing output name");
  }
  rd.expect("end");
  if (names) *names = std::move(nm);
  const detail::Problem pb(md.S, md.Y, md.trend, md.corr);
  const Eigen::VectorXd theta = md.theta;  // not md.theta: md is moved in the same call
  const double nugget = md.nugget;
  return assemble(pb, theta, nugget, std::move(md));
}

}  // namespace smi::surrogate::kriging
