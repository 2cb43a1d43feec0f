// core/state_archive.h: named records round-trip to the bit; a damaged, truncated or
// foreign file, a missing record and a record sized for another model are refused with
// CheckpointError naming the file.
#include "core/state_archive.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <vector>

namespace {

using crashlink::CheckpointError;
using crashlink::core::StateReader;
using crashlink::core::StateWriter;

std::string temp_file(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / "crashlink_state_archive";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string what_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "(no CheckpointError)";
}

TEST(StateArchive, RoundTripsEveryTypeToTheBit) {
  const std::vector<double> d{1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(),
                              std::numeric_limits<double>::infinity(), 6.02214076e23};
  const std::vector<std::int32_t> i32{-1, 0, 2147483647};
  const std::vector<std::int8_t> i8{-1, 1, 0};
  struct Pod {
    double a[3];
    std::int64_t b;
  } pod{{1.5, 2.5, 3.5}, -7};
  StateWriter w;
  w.put("d", std::span<const double>(d));
  w.put("i32", std::span<const std::int32_t>(i32));
  w.put("i8", std::span<const std::int8_t>(i8));
  w.put("empty", std::span<const double>());
  w.put_int("n", -42);
  w.put_bool("flag", true);
  w.put_string("name", "wiper");
  w.put_pod("pod", pod);
  const std::string path = temp_file("roundtrip.bin");
  w.save(path);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

  const StateReader r(path);
  std::vector<double> d2;
  r.get("d", d2);
  ASSERT_EQ(d2.size(), d.size());
  for (std::size_t k = 0; k < d.size(); ++k) {
    EXPECT_EQ(std::signbit(d2[k]), std::signbit(d[k]));
    EXPECT_EQ(d2[k], d[k]);
  }
  std::vector<std::int32_t> i32b;
  r.get("i32", i32b);
  EXPECT_EQ(i32b, i32);
  std::vector<std::int8_t> i8b;
  r.get("i8", i8b);
  EXPECT_EQ(i8b, i8);
  std::vector<double> e{9.0};
  r.get("empty", e);
  EXPECT_TRUE(e.empty());
  EXPECT_EQ(r.get_int("n"), -42);
  EXPECT_TRUE(r.get_bool("flag"));
  EXPECT_EQ(r.get_string("name"), "wiper");
  Pod back{};
  r.get_pod("pod", back);
  EXPECT_EQ(back.a[1], 2.5);
  EXPECT_EQ(back.b, -7);
}

TEST(StateArchive, RefusesDamagedTruncatedAndForeignFiles) {
  const std::vector<double> d(100, 1.25);
  StateWriter w;
  w.put("u", std::span<const double>(d));
  const std::string path = temp_file("damaged.bin");
  w.save(path);
  std::vector<char> bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto write = [&](const std::vector<char>& b) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
  };
  auto flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;  // one bit inside the data
  write(flipped);
  EXPECT_NE(what_of([&] { StateReader r(path); }).find("checksum"), std::string::npos);
  write(std::vector<char>(bytes.begin(), bytes.begin() + 200));  // killed while writing
  EXPECT_NE(what_of([&] { StateReader r(path); }).find(path), std::string::npos);
  write(std::vector<char>{'n', 'o', 't', ' ', 'a', ' ', 'c', 'h', 'e', 'c', 'k', 'p', 'o', 'i',
                          'n', 't', ' ', 'f', 'i', 'l', 'e', '.', '.', '.', '.', '.', '.', '.'});
  EXPECT_NE(what_of([&] { StateReader r(path); }).find("header"), std::string::npos);
  EXPECT_NE(what_of([&] { StateReader r(temp_file("absent.bin")); }).find("cannot open"),
            std::string::npos);
}

TEST(StateArchive, MissingRecordsAndOtherSizesAreNamed) {
  const std::vector<double> d(12, 0.5);
  StateWriter w;
  w.put("u", std::span<const double>(d));
  const std::string path = temp_file("sizes.bin");
  w.save(path);
  const StateReader r(path);
  std::vector<double> model_sized(15, 0.0);
  const std::string size = what_of([&] { r.get_exact("u", model_sized); });
  EXPECT_NE(size.find("'u' has 12 values, this model needs 15"), std::string::npos) << size;
  const std::string missing = what_of([&] { (void)r.get_double("v"); });
  EXPECT_NE(missing.find("no record 'v'"), std::string::npos) << missing;
  const std::string type = what_of([&] { (void)r.get_int("u"); });
  EXPECT_NE(type.find("holds double values, expected int64"), std::string::npos) << type;
}

}  // namespace
