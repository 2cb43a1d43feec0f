// The coordinator's interface-history file (solver/io/coupling_history_writer.h; layout:
// docs/result-format.md, "coordinator.h5") read back with the HDF5 C API: every row bitwise, the
// units attributes, the interface and timing attributes, the flush on destruction.
#include "solver/io/coupling_history_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

using test::fresh_dir;
using test::H5Reader;

/// Row i of interface `iface`; every value a small multiple of a power of two, so the expected
/// values do not depend on how the compiler contracts the arithmetic.
CouplingSample row(int iface, int i) {
  const double k = 128.0 * iface;
  const double x = i;
  return CouplingSample{x / 1024.0,  x / 64.0 + k, -x / 4096.0 + k,
                        x * 0.5 + k, -x / 4.0 + k, {x + k, -2.0 * x, 3.0 + k}};
}

std::string units(const H5Reader& r, const std::string& path) {
  return r.attr_string(path, "units");
}

TEST(CouplingHistoryWriter, RoundTripRowsUnitsAndAttributes) {
  const std::string path = fresh_dir("round_trip") + "/coordinator.h5";
  constexpr int kRows = 2500;  // more than kFlushSamples: buffered flushes and the final one
  {
    CouplingHistoryWriter w(path);
    const std::size_t a = w.add_interface("fine-coarse", "link", "fine", "coarse", "layer", 12);
    const std::size_t b =
        w.add_interface("head/plate", "contact:head_on_plate", "head", "plate", "paper", 3);
    EXPECT_EQ(a, 0u);
    EXPECT_EQ(b, 1u);
    for (int i = 0; i < kRows; ++i) {
      w.append(a, row(0, i));
      if (i % 2 == 0) w.append(b, row(1, i));
    }
    EXPECT_THROW(w.append(2, row(0, 0)), ResultFileError);
    w.write_timing(12.5, 0.75, {{"fine", 0.5}, {"coarse", 0.0}});
    w.write_timing(13.5, 0.8, {{"fine", 0.6}, {"coarse", 0.1}});  // replaced, not duplicated
  }  // destructor flushes the last rows

  const H5Reader r(path);
  EXPECT_EQ(r.attr_string("/", "format"), "crashlink-coupling");
  EXPECT_EQ(r.attr_int64("/", "format_version"), 1);
  const std::string ga = "/coupling/fine-coarse";
  const std::string gb = "/coupling/head_plate";  // '/' sanitised like other link names
  ASSERT_TRUE(r.exists(ga));
  ASSERT_TRUE(r.exists(gb));
  EXPECT_EQ(r.attr_string(gb, "name"), "head/plate");
  EXPECT_EQ(r.attr_string(gb, "kind"), "contact:head_on_plate");
  EXPECT_EQ(r.attr_string(gb, "fine"), "head");
  EXPECT_EQ(r.attr_string(gb, "coarse"), "plate");
  EXPECT_EQ(r.attr_string(gb, "scheme"), "paper");
  EXPECT_EQ(r.attr_int64(gb, "j_nodes"), 3);
  EXPECT_EQ(r.attr_string(ga, "kind"), "link");
  EXPECT_EQ(r.attr_string(ga, "scheme"), "layer");
  EXPECT_EQ(r.attr_int64(ga, "j_nodes"), 12);

  for (int iface = 0; iface < 2; ++iface) {
    const std::string g = iface == 0 ? ga : gb;
    const std::size_t k = iface == 0 ? kRows : (kRows + 1) / 2;
    const auto t = r.doubles(g + "/time");
    const auto vj = r.doubles(g + "/velocity_jump");
    const auto gap = r.doubles(g + "/displacement_gap");
    const auto lw = r.doubles(g + "/link_work");
    const auto dw = r.doubles(g + "/drift_work");
    const auto f = r.doubles(g + "/force");
    ASSERT_EQ(t.size(), k);
    ASSERT_EQ(r.dims(g + "/force"), (std::vector<hsize_t>{k, 3}));
    for (std::size_t j = 0; j < k; ++j) {
      const int i = iface == 0 ? static_cast<int>(j) : static_cast<int>(2 * j);
      const CouplingSample s = row(iface, i);
      EXPECT_EQ(t[j], s.time_s);
      EXPECT_EQ(vj[j], s.velocity_jump_m_s);
      EXPECT_EQ(gap[j], s.displacement_gap_m);
      EXPECT_EQ(lw[j], s.link_work_J);
      EXPECT_EQ(dw[j], s.drift_work_J);
      for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(f[3 * j + c], s.force_N[c]);
    }
    EXPECT_EQ(units(r, g + "/time"), "s");
    EXPECT_EQ(units(r, g + "/velocity_jump"), "m/s");
    EXPECT_EQ(units(r, g + "/displacement_gap"), "m");
    EXPECT_EQ(units(r, g + "/link_work"), "J");
    EXPECT_EQ(units(r, g + "/drift_work"), "J");
    EXPECT_EQ(units(r, g + "/force"), "N");
  }
  EXPECT_EQ(r.attr_double("/timing", "wall_seconds"), 13.5);
  EXPECT_EQ(r.attr_double("/timing", "coordinator_cpu_seconds"), 0.8);
  EXPECT_EQ(r.attr_double("/timing/fine", "wait_seconds"), 0.6);
  EXPECT_EQ(r.attr_double("/timing/coarse", "wait_seconds"), 0.1);
  EXPECT_EQ(r.attr_string("/timing/coarse", "name"), "coarse");
}

TEST(CouplingHistoryWriter, FlushMakesRowsVisibleWhileOpenAndNamesStayUnique) {
  const std::string path = fresh_dir("flush") + "/coordinator.h5";
  CouplingHistoryWriter w(path);
  const std::size_t a = w.add_interface("i", "link", "f", "c", "layer", 1);
  const std::size_t b = w.add_interface("i", "link", "f", "c2", "layer", 2);  // repeated name
  w.add_interface("", "link", "f", "c3", "layer", 0);                         // empty name
  for (int i = 0; i < 5; ++i) w.append(a, row(0, i));
  w.append(b, row(1, 0));
  w.flush();
  const H5Reader r(path);  // the file is open for writing in this process; readable after flush
  EXPECT_EQ(r.doubles("/coupling/i/time").size(), 5u);
  EXPECT_EQ(r.attr_string("/coupling/i_1", "coarse"), "c2");
  EXPECT_EQ(r.doubles("/coupling/i_1/time").size(), 1u);
  EXPECT_TRUE(r.exists("/coupling/interface_2"));
  EXPECT_FALSE(r.exists("/timing"));
}

TEST(CouplingHistoryWriter, UnwritablePathThrowsResultFileErrorNamingIt) {
  const std::string path = fresh_dir("bad") + "/no/such/dir/coordinator.h5";
  try {
    CouplingHistoryWriter w(path);
    FAIL() << "no exception";
  } catch (const ResultFileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace crashlink::io
