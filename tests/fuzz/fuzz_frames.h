#pragma once
// The byte layout of the message fuzz targets (coordinator_fuzz.cpp, daemon_fuzz.cpp): one flags
// byte, then frames [tag: 1 byte][length: 2 bytes little-endian][length bytes], each frame one
// ZeroMQ message (a serialized wire::Envelope, or garbage) from the peer `tag` picks. A frame
// cut short by the end of the input keeps the bytes that are there.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace crashlink::fuzz {

struct Frame {
  std::uint8_t tag = 0;
  std::span<const std::uint8_t> bytes;
};

class FrameReader {
 public:
  FrameReader(const std::uint8_t* data, std::size_t size) : rest_(data, size) {}

  /// The flags byte (0 when the input is empty).
  std::uint8_t flags() {
    if (rest_.empty()) return 0;
    const std::uint8_t f = rest_[0];
    rest_ = rest_.subspan(1);
    return f;
  }

  std::optional<Frame> next() {
    if (rest_.empty()) return std::nullopt;
    Frame f;
    f.tag = rest_[0];
    std::size_t length = 0;
    if (rest_.size() >= 2) length = rest_[1];
    if (rest_.size() >= 3) length |= static_cast<std::size_t>(rest_[2]) << 8;
    rest_ = rest_.subspan(std::min<std::size_t>(3, rest_.size()));
    length = std::min(length, rest_.size());
    f.bytes = rest_.first(length);
    rest_ = rest_.subspan(length);
    return f;
  }

 private:
  std::span<const std::uint8_t> rest_;
};

/// One frame as FrameReader reads it (seed corpus writer).
inline std::string frame(std::uint8_t tag, const std::string& bytes) {
  std::string out(1, static_cast<char>(tag));
  out.push_back(static_cast<char>(bytes.size() & 0xff));
  out.push_back(static_cast<char>((bytes.size() >> 8) & 0xff));
  return out + bytes.substr(0, 0xffff);
}

}  // namespace crashlink::fuzz
