#include "solver/run/checkpoint_store.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "solver/core/state_archive.h"

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
  throw CheckpointError(
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

}  // namespace

std::string checkpoint_folder(const std::string& out, std::int64_t ticks, const std::string& who) {
  return (root(out) / instant_name(ticks) / who).string();
}

std::vector<std::int64_t> list_checkpoints(const std::string& out, const std::string& who) {
  std::vector<std::int64_t> found;
  std::error_code ec;
  if (!fs::is_directory(root(out), ec)) return found;
  for (const auto& e : fs::directory_iterator(root(out), ec)) {
    std::int64_t t = 0;
    if (!e.is_directory() || !parse_instant(e.path().filename().string(), t)) continue;
    if (fs::is_directory(e.path() / who, ec)) found.push_back(t);
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string begin_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who) {
  const fs::path tmp = root(out) / instant_name(ticks) / ("." + who + ".tmp");
  std::error_code ec;
  fs::remove_all(tmp, ec);
  if (!fs::create_directories(tmp, ec) && ec) fail(tmp, "create_directories", ec);
  return tmp.string();
}

void commit_checkpoint(const std::string& out, std::int64_t ticks, const std::string& who,
                       std::size_t keep) {
  const fs::path instant = root(out) / instant_name(ticks);
  const fs::path tmp = instant / ("." + who + ".tmp");
  const fs::path final_path = instant / who;
  std::error_code ec;
  fs::remove_all(final_path, ec);
  fs::rename(tmp, final_path, ec);
  if (ec) fail(final_path, "rename from " + tmp.string(), ec);
  sync(instant);
  auto all = list_checkpoints(out, who);
  if (all.size() <= keep) return;
  for (std::size_t i = 0; i + keep < all.size(); ++i) {
    const fs::path old = root(out) / instant_name(all[i]);
    fs::remove_all(old / who, ec);
    if (fs::is_empty(old, ec)) fs::remove(old, ec);
  }
}

void remove_checkpoints(const std::string& out, const std::string& who) {
  std::error_code ec;
  if (!fs::is_directory(root(out), ec)) return;
  for (const auto& e : fs::directory_iterator(root(out), ec)) {
    if (!e.is_directory()) continue;
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
