// SPDX-License-Identifier: MIT
// smi-lua report --pdf HTML: a study's report.html printed to report.pdf beside it, A4, through
// headless Chromium (--print-to-pdf), which lays the page out with the report's print styles
// (smi.report.style: tables in the page width, figures never cut). A study run with --pdf does
// the same after it wrote its report (main.cpp). Where no Chromium is installed, the message
// says how to get one, or to print report.html from any browser.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "platform/eval/process.hpp"

namespace smi::cli {
namespace fs = std::filesystem;

namespace {

/// The Chromium to print with: $CHROMIUM, else the first of the usual names on PATH; "" if none.
std::string find_chromium() {
  if (const char* c = std::getenv("CHROMIUM"); c && *c) return eval::find_program(c);
  for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"}) {
    const std::string p = eval::find_program(name);
    if (!p.empty()) return p;
  }
  return "";
}

}  // namespace

int print_report_pdf(const std::string& html) {
  std::error_code ec;
  const fs::path in = fs::absolute(html, ec);
  if (ec || !fs::is_regular_file(in, ec)) {
    std::fprintf(stderr, "smi-lua report --pdf: %s is not a file: give the report.html a study wrote\n", html.c_str());
    return 1;
  }
  const fs::path out = fs::path(in).replace_extension(".pdf");
  const std::string chromium = find_chromium();
  if (chromium.empty()) {
    std::fprintf(stderr,
                 "smi-lua: no PDF: headless Chromium prints it and none was found (chromium on PATH, or $CHROMIUM). "
                 "Install it (Debian: apt-get install chromium), then run: smi-lua report --pdf %s; or open %s in a "
                 "browser and print it to PDF (A4)\n",
                 in.c_str(), in.c_str());
    return 1;
  }
  // A profile of its own, removed after: nothing of the user's browser is read or changed.
  const fs::path profile = fs::temp_directory_path(ec) / ("smi-lua-pdf-" + std::to_string(::getpid()));
  fs::create_directories(profile, ec);
  eval::SpawnSpec spec;
  spec.program = chromium;
  spec.argv = {chromium, "--headless", "--disable-gpu", "--no-sandbox", "--no-first-run", "--disable-sync",
               "--disable-background-networking", "--disable-component-update", "--no-pdf-header-footer",
               "--user-data-dir=" + profile.string(), "--print-to-pdf=" + out.string(), "file://" + in.string()};
  spec.workdir = in.parent_path().string();
  spec.env = eval::current_environment();
  spec.solver_mark = false;
  fs::remove(out, ec);
  eval::CapturedRun r;
  try {
    r = eval::run_captured(spec, 120);  // literal: seconds a report may take to print
  } catch (const std::exception& e) {
    fs::remove_all(profile, ec);
    std::fprintf(stderr, "smi-lua: no PDF: %s\n", e.what());
    return 1;
  }
  fs::remove_all(profile, ec);
  if (r.timed_out || !fs::is_regular_file(out, ec) || fs::file_size(out, ec) == 0) {
    std::fprintf(stderr, "smi-lua: no PDF: %s %s; open %s in a browser and print it to PDF (A4)\n", chromium.c_str(),
                 r.timed_out ? "did not finish in 120 s" : "wrote nothing", in.c_str());
    return 1;
  }
  std::printf("pdf:     %s\n", out.c_str());
  std::fflush(stdout);
  return 0;
}

int cmd_report(const Args&, const std::vector<std::string>& args) {
  if (args.size() != 2 || args[0] != "--pdf") {
    std::fprintf(stderr, "usage: smi-lua report --pdf REPORT.html   (prints it to REPORT.pdf beside it)\n");
    return 2;
  }
  return print_report_pdf(args[1]);
}

}  // namespace smi::cli
