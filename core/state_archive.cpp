#include "core/state_archive.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace crashlink::core {

namespace {

constexpr char kMagic[16] = {'C', 'R', 'A', 'S', 'H', 'L', 'I', 'N',
                             'K', '-', 'S', 'T', 'A', 'T', 'E', '\n'};
constexpr std::uint32_t kFormatVersion = 1;

enum Type : std::uint8_t { F64 = 1, I64 = 2, I32 = 3, U8 = 4, I8 = 5, STR = 6 };

std::size_t type_size(std::uint8_t t) {
  switch (t) {
    case F64:
    case I64:
      return 8;
    case I32:
      return 4;
    case U8:
    case I8:
    case STR:
      return 1;
    default:
      return 0;
  }
}

const char* type_name(std::uint8_t t) {
  switch (t) {
    case F64:
      return "double";
    case I64:
      return "int64";
    case I32:
      return "int32";
    case U8:
      return "uint8";
    case I8:
      return "int8";
    case STR:
      return "string";
    default:
      return "unknown";
  }
}

template <class T>
void append_raw(std::vector<std::uint8_t>& out, const T& x) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&x);
  out.insert(out.end(), p, p + sizeof x);
}

[[noreturn]] void sys_fail(const std::string& path, const char* what) {
  throw IoError(
      fmt::format("checkpoint {}: {} failed: {}; check that the output folder "
                  "is writable and the disk is not full",
                  path, what, std::strerror(errno)));
}

void fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) sys_fail(path, "open for fsync");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) sys_fail(path, "fsync");
}

}  // namespace

std::uint64_t fnv1a(const std::uint8_t* p, std::size_t n, std::uint64_t h) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

void StateWriter::record(std::string_view name, std::uint8_t type, std::size_t count,
                         const void* data, std::size_t bytes) {
  append_raw(body_, static_cast<std::uint32_t>(name.size()));
  body_.insert(body_.end(), name.begin(), name.end());
  append_raw(body_, type);
  append_raw(body_, static_cast<std::uint64_t>(count));
  const auto* p = static_cast<const std::uint8_t*>(data);
  if (bytes > 0) body_.insert(body_.end(), p, p + bytes);
}

void StateWriter::put(std::string_view name, std::span<const double> v) {
  record(name, F64, v.size(), v.data(), v.size_bytes());
}
void StateWriter::put(std::string_view name, std::span<const std::int64_t> v) {
  record(name, I64, v.size(), v.data(), v.size_bytes());
}
void StateWriter::put(std::string_view name, std::span<const std::int32_t> v) {
  record(name, I32, v.size(), v.data(), v.size_bytes());
}
void StateWriter::put(std::string_view name, std::span<const std::uint8_t> v) {
  record(name, U8, v.size(), v.data(), v.size_bytes());
}
void StateWriter::put(std::string_view name, std::span<const std::int8_t> v) {
  record(name, I8, v.size(), v.data(), v.size_bytes());
}
void StateWriter::put_string(std::string_view name, std::string_view s) {
  record(name, STR, s.size(), s.data(), s.size());
}

void StateWriter::save(const std::string& path) const {
  std::vector<std::uint8_t> file(std::begin(kMagic), std::end(kMagic));
  append_raw(file, kFormatVersion);
  file.insert(file.end(), body_.begin(), body_.end());
  append_raw(file, fnv1a(file.data(), file.size()));
  const std::string tmp = path + ".tmp";
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) sys_fail(tmp, "fopen");
    const bool ok = std::fwrite(file.data(), 1, file.size(), f) == file.size();
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed) sys_fail(tmp, "write");
  }
  fsync_path(tmp, false);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) sys_fail(path, "rename");
  const auto dir = std::filesystem::path(path).parent_path();
  fsync_path(dir.empty() ? std::string(".") : dir.string(), true);
}

StateReader::StateReader(std::string path) : path_(std::move(path)) {
  std::ifstream in(path_, std::ios::binary);
  if (!in) {
    throw CheckpointError(
        fmt::format("checkpoint {}: cannot open it; is the checkpoint folder "
                    "complete (written by a run that reached this instant)?",
                    path_));
  }
  bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::size_t head = sizeof kMagic + sizeof(std::uint32_t);
  auto damaged = [&](const std::string& why) {
    return CheckpointError(fmt::format(
        "checkpoint {}: {}; the file is damaged or not a crashlink checkpoint: restart from an "
        "earlier checkpoint (delete this one) or run from the start",
        path_, why));
  };
  if (bytes_.size() < head + 8 || std::memcmp(bytes_.data(), kMagic, sizeof kMagic) != 0)
    throw damaged("no crashlink state header");
  std::uint32_t version = 0;
  std::memcpy(&version, bytes_.data() + sizeof kMagic, sizeof version);
  if (version != kFormatVersion) {
    throw CheckpointError(
        fmt::format("checkpoint {}: format version {}, this build reads {}; "
                    "restart with the build that wrote it",
                    path_, version, kFormatVersion));
  }
  const std::size_t end = bytes_.size() - 8;
  std::uint64_t stored = 0;
  std::memcpy(&stored, bytes_.data() + end, 8);
  if (fnv1a(bytes_.data(), end) != stored) throw damaged("checksum mismatch");
  std::size_t at = head;
  while (at < end) {
    std::uint32_t len = 0;
    if (end - at < 4) throw damaged("truncated record header");
    std::memcpy(&len, bytes_.data() + at, 4);
    at += 4;
    if (end - at < static_cast<std::size_t>(len) + 9) throw damaged("truncated record name");
    std::string name(reinterpret_cast<const char*>(bytes_.data() + at), len);
    at += len;
    Entry e;
    e.type = bytes_[at++];
    std::uint64_t count = 0;
    std::memcpy(&count, bytes_.data() + at, 8);
    at += 8;
    const std::size_t size = type_size(e.type);
    if (size == 0 || count > (end - at) / size) throw damaged("bad record '" + name + "'");
    e.count = static_cast<std::size_t>(count);
    e.offset = at;
    at += e.count * size;
    index_[name] = e;
  }
}

const StateReader::Entry& StateReader::find(std::string_view name, std::uint8_t type) const {
  const auto it = index_.find(std::string(name));
  if (it == index_.end()) {
    throw CheckpointError(
        fmt::format("checkpoint {}: no record '{}'; it was written by another "
                    "version or for another model: run from the start",
                    path_, name));
  }
  if (it->second.type != type) {
    throw CheckpointError(fmt::format("checkpoint {}: record '{}' holds {} values, expected {}",
                                      path_, name, type_name(it->second.type), type_name(type)));
  }
  return it->second;
}

void StateReader::size_mismatch(std::string_view name, std::size_t got, std::size_t want) const {
  throw CheckpointError(
      fmt::format("checkpoint {}: record '{}' has {} values, this model needs "
                  "{}; the checkpoint belongs to another model or domain cut",
                  path_, name, got, want));
}

template <class T>
void StateReader::get_any(std::string_view name, std::uint8_t type, std::vector<T>& v) const {
  const Entry& e = find(name, type);
  v.resize(e.count);
  if (e.count > 0) std::memcpy(v.data(), bytes_.data() + e.offset, e.count * sizeof(T));
}

void StateReader::get(std::string_view name, std::vector<double>& v) const {
  get_any(name, F64, v);
}
void StateReader::get(std::string_view name, std::vector<std::int64_t>& v) const {
  get_any(name, I64, v);
}
void StateReader::get(std::string_view name, std::vector<std::int32_t>& v) const {
  get_any(name, I32, v);
}
void StateReader::get(std::string_view name, std::vector<std::uint8_t>& v) const {
  get_any(name, U8, v);
}
void StateReader::get(std::string_view name, std::vector<std::int8_t>& v) const {
  get_any(name, I8, v);
}

double StateReader::get_double(std::string_view name) const {
  std::vector<double> v;
  get(name, v);
  if (v.size() != 1) size_mismatch(name, v.size(), 1);
  return v[0];
}

std::int64_t StateReader::get_int(std::string_view name) const {
  std::vector<std::int64_t> v;
  get(name, v);
  if (v.size() != 1) size_mismatch(name, v.size(), 1);
  return v[0];
}

std::string StateReader::get_string(std::string_view name) const {
  const Entry& e = find(name, STR);
  return std::string(reinterpret_cast<const char*>(bytes_.data() + e.offset), e.count);
}

}  // namespace crashlink::core
