// SPDX-License-Identifier: MIT
#include "results.hpp"

#include <cmath>
#include <cstdio>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace cfe {

namespace {

std::string fmt(const char* f, auto... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

const char* kEigenHeader =
    "                                              R E A L   E I G E N V A L U E S\n"
    "   MODE    EXTRACTION      EIGENVALUE            RADIANS             CYCLES            GENERALIZED         GENERALIZED\n"
    "    NO.       ORDER                                                                       MASS              STIFFNESS\n";
const char* kLabelHeader =
    "                                              M O D E   L A B E L S\n"
    "   MODE          CYCLES  DIRECTION      PAPER   P(TA)  P(TL)  P(TV)  P(RA)  P(RL)  P(RV)\n";
const char* kPaperName[4] = {"VERTICAL", "LATERAL", "TORSION", "WHEEL_PITCH"};

}  // namespace

Results make_results(Airbag airbag, int dof, const Modes& modes, const Labels& labels, const Eigen::MatrixXd& M) {
  Results r;
  r.airbag = airbag == Airbag::rigid ? "RIGID" : "SPRING";
  r.dof = dof;
  const Eigen::VectorXd f = modes.frequency_hz();
  for (Eigen::Index k = 0; k < modes.lambda.size(); ++k) {
    ModeRow m;
    m.mode = static_cast<int>(k) + 1;
    m.eigenvalue = modes.lambda(k);
    m.radians = std::sqrt(std::max(m.eigenvalue, 0.0));
    m.cycles = f(k);
    m.gen_mass = modes.phi.col(k).dot(M * modes.phi.col(k));
    m.gen_stiffness = m.eigenvalue * m.gen_mass;
    m.direction = direction_name(labels.direction[k]);
    for (int j = 0; j < 6; ++j) m.p[j] = labels.p(k, j);
    r.modes.push_back(m);
  }
  for (int pm = 0; pm < 4; ++pm) {
    const int k = labels.paper[pm];
    r.paper_mode[pm] = k + 1;
    r.paper_hz[pm] = k >= 0 ? f(k) : std::numeric_limits<double>::quiet_NaN();
    if (k >= 0) r.modes[k].paper = pm + 1;
  }
  return r;
}

void write_results(std::ostream& os, const Results& r) {
  os << "1    STEERING COLUMN ANALOG\n"
     << fmt("     AIRBAG MODEL = %-6s   DOF = %d\n", r.airbag.c_str(), r.dof) << "0\n" << kEigenHeader;
  for (const auto& m : r.modes)
    os << fmt("%9d%10d%20.6E%20.6E%20.6E%20.6E%20.6E\n", m.mode, m.mode, m.eigenvalue, m.radians, m.cycles, m.gen_mass,
              m.gen_stiffness);
  os << "0\n" << kLabelHeader;
  for (const auto& m : r.modes) {
    const std::string paper = m.paper ? std::to_string(m.paper) : "-";
    os << fmt("%7d%16.6E  %-12s %6s", m.mode, m.cycles, m.direction.c_str(), paper.c_str());
    for (double p : m.p) os << fmt("%7.3f", p);
    os << "\n";
  }
  os << "0\n";
  for (int pm = 0; pm < 4; ++pm) {
    if (r.paper_mode[pm] > 0)
      os << fmt("     PAPER MODE %d  %-12s  MODE %3d%14.6E HZ\n", pm + 1, kPaperName[pm], r.paper_mode[pm], r.paper_hz[pm]);
    else
      os << fmt("     PAPER MODE %d  %-12s  NOT FOUND\n", pm + 1, kPaperName[pm]);
  }
}

Results read_results(std::istream& is, const std::string& file) {
  Results r;
  std::string line;
  int n = 0;
  enum { head, eig, lab, summary } section = head;
  auto bad = [&](const std::string& what) {
    throw std::runtime_error(file + ":" + std::to_string(n) + ": " + what + ": '" + line + "'");
  };
  while (std::getline(is, line)) {
    ++n;
    std::istringstream ls(line);
    if (line.find("AIRBAG MODEL =") != std::string::npos) {
      std::string w;
      ls >> w >> w >> w >> r.airbag >> w >> w >> r.dof;
      if (!ls) bad("malformed header");
    } else if (line.find("R E A L") != std::string::npos) {
      section = eig;
    } else if (line.find("M O D E") != std::string::npos) {
      section = lab;
    } else if (line.find("PAPER MODE") != std::string::npos) {
      section = summary;
      std::string w;
      int pm = 0;
      ls >> w >> w >> pm >> w;
      if (!ls || pm < 1 || pm > 4) bad("malformed paper-mode line");
      if (line.find("NOT FOUND") != std::string::npos) {
        r.paper_mode[pm - 1] = 0;
        r.paper_hz[pm - 1] = std::numeric_limits<double>::quiet_NaN();
      } else if (!(ls >> w >> r.paper_mode[pm - 1] >> r.paper_hz[pm - 1])) {
        bad("malformed paper-mode line");
      }
    } else if (section == eig && line.size() > 20 && std::isdigit(static_cast<unsigned char>(line[8]))) {
      ModeRow m;
      int order = 0;
      if (!(ls >> m.mode >> order >> m.eigenvalue >> m.radians >> m.cycles >> m.gen_mass >> m.gen_stiffness))
        bad("malformed eigenvalue line");
      r.modes.push_back(m);
    } else if (section == lab && line.size() > 20 && std::isdigit(static_cast<unsigned char>(line[6]))) {
      int mode = 0;
      double cyc = 0;
      std::string dir, paper;
      if (!(ls >> mode >> cyc >> dir >> paper)) bad("malformed label line");
      if (mode < 1 || mode > static_cast<int>(r.modes.size())) bad("label for a mode not in the eigenvalue table");
      ModeRow& m = r.modes[mode - 1];
      m.direction = dir;
      m.paper = paper == "-" ? 0 : std::atoi(paper.c_str());
      for (double& p : m.p)
        if (!(ls >> p)) bad("malformed participation factors");
    }
  }
  if (r.modes.empty()) throw std::runtime_error(file + ": no eigenvalue table found (not a smi-column-fe results file?)");
  return r;
}

}  // namespace cfe
