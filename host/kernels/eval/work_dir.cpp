#include "eval/work_dir.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "core/errors.hpp"

namespace smi::eval {
namespace fs = std::filesystem;

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw Error(fmt::format("error writing '{}' (disk full?)", path));
}

void prepare_work_dir(const std::string& dir, const std::string& deck_name, const std::string& deck_text,
                      const std::vector<std::string>& files) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) throw Error(fmt::format("cannot clear work directory '{}': {}", dir, ec.message()));
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("cannot create work directory '{}': {}", dir, ec.message()));
  if (!deck_name.empty()) write_text_file((fs::path(dir) / deck_name).string(), deck_text);
  for (const auto& f : files) {
    const fs::path to = fs::path(dir) / fs::path(f).filename();
    fs::copy_file(f, to, fs::copy_options::overwrite_existing, ec);
    if (ec) throw Error(fmt::format("cannot copy '{}' into '{}': {}", f, dir, ec.message()));
  }
}

}  // namespace smi::eval
