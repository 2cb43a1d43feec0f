#include "solver/run/checkpoint_store.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

#include "core/state_archive.h"

namespace crashlink::run {

namespace fs = std::filesystem;

namespace {

fs::path root(const std::string& out) {
  return fs::path(out) / "checkpoints";
}

std::string instant_name(std::int64_t ticks) {
  return fmt::format("{:020d}", ticks);
}

[[noreturn]] void fail(const fs::path& p, const std::string& what, const std::error_code& ec) {
  throw IoError(
      fmt::format("checkpoint {}: {}: {}; check that the output folder is "
                  "writable and the disk is not full",
                  p.string(), what, ec.message()));
}

void sync(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY);
  if (fd < 0) return;  // best effort: the rename itself is atomic
  (void)::fsync(fd);
  ::close(fd);
}

bool parse_instant(const std::string& name, std::int64_t& ticks) {
  if (name.size() != 20 || !std::all_of(name.begin(), name.end(), ::isdigit)) return false;
  ticks = std::stoll(name);
  return true;
}

/// The instant folders OUT/checkpoints/<T>, each with its T, in no order.
std::vector<std::pair<std::int64_t, fs::path>> instant_folders(const std::string& out) {
  std::vector<std::pair<std::int64_t, fs::path>> found;
  std::error_code ec;
  if (!fs::is_directory(root(out), ec)) return found;
  for (const auto& e : fs::directory_iterator(root(out), ec)) {
    std::int64_t t = 0;
    if (e.is_directory(ec) && parse_instant(e.path().filename().string(), t))
      found.emplace_back(t, e.path());
  }
  return found;
}

constexpr const char* kManifest = "MANIFEST";
constexpr const char* kManifestHead = "crashlink-checkpoint-manifest 1";

/// FNV-1a 64 of a whole file and its size in bytes; false if it cannot be read.
bool hash_file(const fs::path& p, std::uint64_t& hash, std::uintmax_t& bytes) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  std::vector<std::uint8_t> buf(std::size_t{1} << 20);
  hash = core::fnv1a(nullptr, 0);
  bytes = 0;
  while (in) {
    in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(buf.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    hash = core::fnv1a(buf.data(), n, hash);
    bytes += n;
  }
  return in.eof();
}

/// MANIFEST: a head line, then "<hash, 16 hex digits> <bytes> <file name>" per regular file.
void write_manifest(const fs::path& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file() && e.path().filename() != kManifest) files.push_back(e.path());
  if (ec) fail(folder, "listing", ec);
  std::sort(files.begin(), files.end());
  std::ostringstream text;
  text << kManifestHead << "\n";
  for (const auto& f : files) {
    std::uint64_t h = 0;
    std::uintmax_t n = 0;
    if (!hash_file(f, h, n)) fail(f, "reading back", std::make_error_code(std::errc::io_error));
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016" PRIx64, h);
    text << hex << ' ' << n << ' ' << f.filename().string() << "\n";
  }
  const fs::path m = folder / kManifest;
  {
    std::ofstream out(m, std::ios::binary | std::ios::trunc);
    out << text.str();
    out.flush();
    if (!out) fail(m, "write", std::make_error_code(std::errc::io_error));
  }
  sync(m);
}

}  // namespace

std::string checkpoint_folder(const std::string& out, std::int64_t ticks, const std::string& who) {
  return (root(out) / instant_name(ticks) / who).string();
}

std::vector<std::int64_t> list_checkpoints(const std::string& out, const std::string& who) {
  std::vector<std::int64_t> found;
  std::error_code ec;
  for (const auto& [t, folder] : instant_folders(out))
    if (fs::is_directory(folder / who, ec)) found.push_back(t);
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<std::string> checkpoint_owners(const std::string& out) {
  std::vector<std::string> who;
  std::error_code ec;
  for (const auto& instant : instant_folders(out)) {
    for (const auto& piece : fs::directory_iterator(instant.second, ec)) {
      const std::string name = piece.path().filename().string();
      if (piece.is_directory() && !name.starts_with(".")) who.push_back(name);  // not a .tmp
    }
  }
  std::sort(who.begin(), who.end());
  who.erase(std::unique(who.begin(), who.end()), who.end());
  return who;
}

std::string verify_checkpoint(const std::string& folder) {
  std::ifstream in(fs::path(folder) / kManifest);
  std::string line;
  if (!in || !std::getline(in, line) || line != kManifestHead)
    return std::string("no ") + kManifest + " (the checkpoint was not committed by this version)";
  std::size_t listed = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string hex, name;
    std::uintmax_t want_bytes = 0;
    if (!(row >> hex >> want_bytes) || !std::getline(row >> std::ws, name) || name.empty())
      return fmt::format("{} line {} unreadable: '{}'", kManifest, listed + 2, line);
    ++listed;
    std::uint64_t h = 0;
    std::uintmax_t n = 0;
    if (!hash_file(fs::path(folder) / name, h, n)) return fmt::format("{}: missing", name);
    if (n != want_bytes) return fmt::format("{}: {} bytes, {} when written", name, n, want_bytes);
    if (fmt::format("{:016x}", h) != hex)
      return fmt::format("{}: FNV-1a {:016x}, {} when written (the file was changed)", name, h,
                         hex);
  }
  if (listed == 0) return std::string(kManifest) + " lists no file";
  return {};
}

std::vector<std::int64_t> list_sound_checkpoints(const std::string& out, const std::string& who,
                                                 std::vector<std::string>* damaged) {
  std::vector<std::int64_t> sound;
  for (const auto t : list_checkpoints(out, who)) {
    const std::string folder = checkpoint_folder(out, t, who);
    const std::string why = verify_checkpoint(folder);
    if (why.empty()) {
      sound.push_back(t);
    } else if (damaged != nullptr) {
      damaged->push_back(folder + ": " + why);
    }
  }
  return sound;
}

std::vector<std::int64_t> complete_instants(const std::string& out,
                                            const std::vector<std::string>& pieces) {
  std::vector<std::int64_t> common;
  bool first = true;
  for (const auto& who : pieces) {
    const auto mine = list_checkpoints(out, who);
    if (first) {
      common = mine;
      first = false;
      continue;
    }
    std::vector<std::int64_t> both;
    std::set_intersection(common.begin(), common.end(), mine.begin(), mine.end(),
                          std::back_inserter(both));
    common = std::move(both);
  }
  return common;
}

std::string begin_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who) {
  const fs::path tmp = root(out) / instant_name(ticks) / ("." + who + ".tmp");
  std::error_code ec;
  fs::remove_all(tmp, ec);
  // Another piece removes an instant's folder once it is empty and older than the kept complete
  // instants, which this one has then passed; a retry covers a removal between the parent's
  // creation and the child's all the same.
  for (int attempt = 0; attempt < 5; ++attempt) {
    ec.clear();
    if (fs::create_directories(tmp, ec) || (!ec && fs::is_directory(tmp))) return tmp.string();
    if (ec != std::errc::no_such_file_or_directory) break;
  }
  fail(tmp, "create_directories", ec);
}

void commit_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who,
                       const std::vector<std::string>& pieces, std::size_t keep) {
  const fs::path instant = root(out) / instant_name(ticks);
  const fs::path tmp = instant / ("." + who + ".tmp");
  const fs::path final_path = instant / who;
  write_manifest(tmp);
  std::error_code ec;
  fs::remove_all(final_path, ec);
  fs::rename(tmp, final_path, ec);
  if (ec) fail(final_path, "rename from " + tmp.string(), ec);
  sync(instant);
  prune_checkpoints(out, pieces, {who}, keep);
}

void prune_checkpoints(const std::string& out, const std::vector<std::string>& pieces,
                       const std::vector<std::string>& whose, std::size_t keep) {
  const auto complete = complete_instants(out, pieces);
  if (keep == 0 || complete.size() < keep) return;
  const std::int64_t oldest_kept = complete[complete.size() - keep];
  std::error_code ec;
  for (const auto& [t, instant] : instant_folders(out)) {
    if (t >= oldest_kept) continue;
    for (const auto& who : whose) {
      fs::remove_all(instant / who, ec);
      fs::remove_all(instant / ("." + who + ".tmp"), ec);
    }
    if (fs::is_empty(instant, ec)) fs::remove(instant, ec);
  }
}

std::vector<std::string> checkpoint_pieces(std::vector<std::string> domains,
                                           bool with_coordinator) {
  if (with_coordinator) domains.emplace_back(kCoordinatorPiece);
  return domains;
}

void remove_checkpoints(const std::string& out, const std::string& who) {
  std::error_code ec;
  if (!fs::is_directory(root(out), ec)) return;
  for (const auto& e : fs::directory_iterator(root(out), ec)) {
    if (!e.is_directory(ec)) continue;
    fs::remove_all(e.path() / who, ec);
    fs::remove_all(e.path() / ("." + who + ".tmp"), ec);
    if (fs::is_empty(e.path(), ec)) fs::remove(e.path(), ec);
  }
}

void copy_into_checkpoint(const std::string& file, const std::string& folder) {
  const fs::path to = fs::path(folder) / fs::path(file).filename();
  std::error_code ec;
  fs::copy_file(file, to, fs::copy_options::overwrite_existing, ec);
  if (ec) fail(to, "copy of " + file, ec);
  sync(to);
}

}  // namespace crashlink::run
