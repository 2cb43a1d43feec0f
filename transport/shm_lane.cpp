#include "transport/shm_lane.h"

#include <fmt/format.h>

#include <filesystem>
#include <thread>

#include "transport/errors.h"

namespace crashlink::transport {

using Clock = std::chrono::steady_clock;

void remove_shm_lane_files(std::string_view endpoint, const std::vector<std::string>& partners) {
  if (endpoint.substr(0, kShmScheme.size()) != kShmScheme) return;
  const std::string prefix(endpoint.substr(kShmScheme.size()));
  std::error_code ec;
  std::filesystem::remove(prefix + ".bell", ec);
  for (const auto& p : partners) std::filesystem::remove(prefix + ".from." + p, ec);
}

ShmLaneIn::ShmLaneIn(std::string prefix, std::chrono::microseconds spin)
    : prefix_(std::move(prefix)),
      endpoint_(std::string(kShmScheme) + prefix_),
      spin_(spin),
      bell_(ShmDoorbell::create(prefix_ + ".bell")) {}

void ShmLaneIn::add_partner(const std::string& domain, std::size_t capacity) {
  std::size_t cap = ShmQueue::kDefaultCapacity;
  while (cap < capacity) cap *= 2;
  queues_.emplace_back(domain, ShmQueue::create(prefix_ + ".from." + domain, cap));
}

bool ShmLaneIn::poll_once(std::string& from, std::string& bytes) {
  for (std::size_t k = 0; k < queues_.size(); ++k) {
    auto& [partner, q] = queues_[(next_ + k) % queues_.size()];
    if (q.pop_into(bytes)) {
      next_ = (next_ + k + 1) % queues_.size();
      from = partner;
      return true;
    }
  }
  return false;
}

bool ShmLaneIn::receive_into(std::chrono::microseconds timeout, std::string& from,
                             std::string& bytes) {
  if (queues_.empty()) {
    std::this_thread::sleep_for(timeout);
    return false;
  }
  const auto t0 = Clock::now();
  const auto deadline = t0 + timeout;
  for (;;) {
    const std::uint32_t seen = bell_.count();
    if (poll_once(from, bytes)) return true;
    const auto now = Clock::now();
    if (now >= deadline) return false;
    if (now - t0 < spin_) continue;  // poll a little before sleeping: a wake-up costs more
    bell_.sleep(seen, std::chrono::duration_cast<std::chrono::microseconds>(deadline - now));
  }
}

bool ShmLaneIn::all_opened() const {
  for (const auto& [partner, q] : queues_)
    if (!q.opened_by_sender()) return false;
  return true;
}

std::optional<std::pair<std::string, std::string>> ShmLaneIn::receive(
    std::chrono::microseconds timeout) {
  std::pair<std::string, std::string> m;
  if (!receive_into(timeout, m.first, m.second)) return std::nullopt;
  return m;
}

ShmLaneOut::ShmLaneOut(std::string_view endpoint, std::string self,
                       std::chrono::milliseconds timeout)
    : self_(std::move(self)), timeout_(timeout) {
  if (endpoint.substr(0, kShmScheme.size()) != kShmScheme) {
    throw TransportError(std::string(endpoint), "a shared-memory lane is named shm://PREFIX");
  }
  prefix_ = std::string(endpoint.substr(kShmScheme.size()));
}

void ShmLaneOut::open(const std::function<void()>& between) {
  // The partner creates its files when it has its Setup, about when we have ours.
  const auto deadline = Clock::now() + timeout_;
  for (;;) {
    // The bell first: opening the queue marks it opened, after which the receiver may end.
    if (!bell_) bell_ = ShmDoorbell::open(prefix_ + ".bell");
    if (bell_ && !queue_) queue_ = ShmQueue::open(prefix_ + ".from." + self_);
    if (queue_ && bell_) return;
    if (Clock::now() >= deadline) {
      throw TransportError(std::string(kShmScheme) + prefix_,
                           fmt::format("the partner's lane files {}.from.{} and {}.bell did not "
                                       "appear within {} ms",
                                       prefix_, self_, prefix_, timeout_.count()));
    }
    if (between) between();
    std::this_thread::sleep_for(std::chrono::microseconds{200});
  }
}

void ShmLaneOut::send(std::string_view bytes) {
  if (!queue_ || !bell_) open();
  queue_->push(bytes, timeout_);
  bell_->ring();
}

}  // namespace crashlink::transport
