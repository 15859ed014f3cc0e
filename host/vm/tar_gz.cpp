// SPDX-License-Identifier: MIT
#include "vm/tar_gz.hpp"

#include <zlib.h>

#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "platform/core/errors.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kBlock = 512;

std::string octal(std::size_t width, unsigned long long v) {
  std::string s(width - 1, '0');
  for (std::size_t i = width - 1; i-- > 0 && v;) {
    s[i] = static_cast<char>('0' + (v & 7));
    v >>= 3;
  }
  return s;  // width-1 digits; the caller leaves the last byte NUL
}

void put(std::string& h, std::size_t at, const std::string& v) { std::memcpy(&h[at], v.data(), v.size()); }

/// One 512-byte ustar header.
std::string header(const TarMember& m) {
  std::string name = m.is_dir ? m.path + "/" : m.path, prefix;
  if (name.size() > 100) {  // ustar: a folder part (prefix, <= 155 bytes) '/' a name (<= 100 bytes)
    std::size_t cut = std::string::npos;
    for (std::size_t p = name.find('/'); p != std::string::npos; p = name.find('/', p + 1))
      if (p > 0 && p <= 155 && name.size() - p - 1 <= 100 && name.size() - p - 1 > 0) {
        cut = p;
        break;
      }
    if (cut == std::string::npos)
      throw Error("cannot pack '" + m.path + "': the name is too long for a tar archive (ustar keeps at most 155 "
                  "bytes of folders and 100 of name); shorten it");
    prefix = name.substr(0, cut);
    name = name.substr(cut + 1);
  }
  std::string h(kBlock, '\0');
  put(h, 0, name);
  put(h, 100, octal(8, m.is_dir || m.executable ? 0755 : 0644));
  put(h, 108, octal(8, 0));
  put(h, 116, octal(8, 0));
  put(h, 124, octal(12, m.is_dir ? 0 : m.data.size()));
  put(h, 136, octal(12, 0));
  h[156] = m.is_dir ? '5' : '0';
  put(h, 257, std::string("ustar\0" "00", 8));
  put(h, 329, octal(8, 0));
  put(h, 337, octal(8, 0));
  put(h, 345, prefix);
  std::memset(&h[148], ' ', 8);
  unsigned sum = 0;
  for (unsigned char c : h) sum += c;
  put(h, 148, octal(7, sum));  // six digits, NUL, then the space already there
  return h;
}

std::string gzip(const std::string& raw, const fs::path& file) {
  z_stream z{};
  // windowBits 15 + 16: a gzip wrapper; zlib writes its header with time 0 and no name.
  if (deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error("cannot compress '" + file.string() + "': zlib failed to start");
  std::string out(deflateBound(&z, raw.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  z.avail_in = static_cast<uInt>(raw.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw Error("cannot compress '" + file.string() + "': zlib error " + std::to_string(rc));
  return out;
}

std::string gunzip(const std::string& gz, const fs::path& file) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) throw Error("cannot read '" + file.string() + "': zlib failed to start");
  std::string out;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data()));
  z.avail_in = static_cast<uInt>(gz.size());
  int rc = Z_OK;
  char buf[1 << 16];
  while (rc != Z_STREAM_END) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      inflateEnd(&z);
      throw Error("'" + file.string() + "' is not a gzip-compressed archive (" + (z.msg ? z.msg : "truncated") +
                  "); give a .tar.gz made by smi-lua libs pack");
    }
    out.append(buf, sizeof buf - z.avail_out);
    if (out.size() > kTarMaxBytes + (1 << 20)) {
      inflateEnd(&z);
      throw Error("'" + file.string() + "' unpacks to more than " + std::to_string(kTarMaxBytes >> 20) +
                  " MiB; a library pack is far smaller (refused as a possible gzip bomb)");
    }
  }
  inflateEnd(&z);
  return out;
}

std::string field(const char* h, std::size_t at, std::size_t n) {
  std::size_t len = 0;
  while (len < n && h[at + len]) ++len;
  return std::string(h + at, len);
}

bool parse_octal(const char* h, std::size_t at, std::size_t n, unsigned long long& v) {
  v = 0;
  std::size_t i = at, end = at + n;
  while (i < end && h[i] == ' ') ++i;
  if (i == end || h[i] < '0' || h[i] > '7') return false;
  for (; i < end && h[i] >= '0' && h[i] <= '7'; ++i) v = v * 8 + static_cast<unsigned>(h[i] - '0');
  for (; i < end; ++i)
    if (h[i] != ' ' && h[i] != '\0') return false;
  return true;
}

const char* type_name(char t) {
  switch (t) {
    case '1': return "a hard link";
    case '2': return "a symbolic link";
    case '3': return "a character device";
    case '4': return "a block device";
    case '6': return "a FIFO";
    case '7': return "a contiguous file";
    case 'x': case 'g': return "a pax extended header";
    case 'L': case 'K': return "a GNU long-name header";
    default: return "an entry of an unknown type";
  }
}

/// "a/./b/" -> "a/b"; refuses absolute names and ".." components.
std::string clean_name(const std::string& raw, const std::string& where) {
  if (raw.empty()) throw Error(where + ": a member has an empty name");
  if (raw[0] == '/')
    throw Error(where + ": member '" + raw + "' has an absolute name; a library pack holds names relative to its folder");
  std::string out;
  std::stringstream ss(raw);
  for (std::string part; std::getline(ss, part, '/');) {
    if (part.empty() || part == ".") continue;
    if (part == "..")
      throw Error(where + ": member '" + raw + "' has a '..' component, which would write outside the install folder");
    out += (out.empty() ? "" : "/") + part;
  }
  if (out.empty()) throw Error(where + ": member '" + raw + "' names no file");
  return out;
}

}  // namespace

void write_tar_gz(const fs::path& file, const std::vector<TarMember>& members) {
  std::string raw;
  for (const TarMember& m : members) {
    raw += header(m);
    if (m.is_dir) continue;
    raw += m.data;
    raw.append((kBlock - m.data.size() % kBlock) % kBlock, '\0');
  }
  raw.append(2 * kBlock, '\0');  // the end-of-archive marker
  const std::string gz = gzip(raw, file);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(gz.data(), static_cast<std::streamsize>(gz.size()));
  out.close();
  if (!out) throw Error("cannot write '" + file.string() + "'");
}

std::vector<TarMember> read_tar_gz(const fs::path& file) {
  const std::string where = "archive '" + file.string() + "'";
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read " + where);
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string raw = gunzip(ss.str(), file);
  std::vector<TarMember> out;
  std::set<std::string> seen;
  std::size_t at = 0;
  for (;;) {
    if (at + kBlock > raw.size()) throw Error(where + " ends without the tar end marker (truncated?)");
    const char* h = raw.data() + at;
    bool zero = true;
    for (std::size_t i = 0; i < kBlock && zero; ++i) zero = h[i] == '\0';
    if (zero) break;
    const std::string short_name = field(h, 0, 100), prefix = field(h, 345, 155);
    const std::string rawname = prefix.empty() ? short_name : prefix + "/" + short_name;
    unsigned long long sum = 0, size = 0, mode = 0;
    unsigned computed = 0;
    for (std::size_t i = 0; i < kBlock; ++i)
      computed += (i >= 148 && i < 156) ? ' ' : static_cast<unsigned char>(h[i]);
    if (!parse_octal(h, 148, 8, sum) || sum != computed)
      throw Error(where + ": the header of member '" + rawname + "' is damaged (checksum mismatch)");
    if (!parse_octal(h, 124, 12, size)) throw Error(where + ": member '" + rawname + "' has an unreadable size");
    parse_octal(h, 100, 8, mode);
    const char type = h[156];
    if (type != '0' && type != '\0' && type != '5') {
      const std::string link = field(h, 157, 100);
      throw Error(where + ": member '" + rawname + "' is " + type_name(type) + (link.empty() ? "" : " (to '" + link + "')") +
                  "; a library pack holds only regular files and folders, so it is refused");
    }
    const std::string name = clean_name(rawname, where);
    if (!seen.insert(name).second) throw Error(where + ": member '" + name + "' appears twice");
    if (out.size() >= kTarMaxMembers)
      throw Error(where + " has more than " + std::to_string(kTarMaxMembers) + " members; a library is far smaller");
    at += kBlock;
    TarMember m;
    m.path = name;
    m.is_dir = type == '5';
    if (!m.is_dir) {
      if (size > raw.size() - at) throw Error(where + ": member '" + name + "' is cut short (truncated archive)");
      m.data = raw.substr(at, size);
      m.executable = (mode & 0100) != 0;
      at += (size + kBlock - 1) / kBlock * kBlock;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace smi::vm
