// /history/contacts/<name>/{time, force}: one row per history sample, resultant force [k,3] in N.
#include <gtest/gtest.h>

#include "solver/io/result_writer.h"
#include "tests/unit/io/result_h5_reader.h"

namespace crashlink::io {
namespace {

TEST(ResultWriter, ContactHistoriesAreWrittenPerInterface) {
  auto m = test::small_model();
  m.contacts.push_back({});
  m.contacts.back().name = "head/plate";  // '/' is not allowed in a link name: becomes '_'
  m.contacts.push_back({});
  m.contacts.back().name = "plate_wiper";
  const auto dir = test::fresh_dir("contacts");
  {
    ResultWriter w(dir, m);
    std::vector<ProbeSample> probes(m.probes.size());
    for (int i = 0; i < 5; ++i) {
      std::vector<ContactSample> c(2);
      for (int k = 0; k < 2; ++k)
        for (int d = 0; d < 3; ++d) c[k].force_N[d] = 100.0 * k + 10.0 * i + d;
      w.append_history(GlstatSample{1e-4 * i}, probes, c);
    }
    EXPECT_THROW(w.append_history(GlstatSample{}, probes, {}), ResultFileError);
  }
  test::H5Reader r(dir + "/result.h5");
  const auto t = r.doubles("/history/contacts/head_plate/time");
  const auto f = r.doubles("/history/contacts/plate_wiper/force");
  ASSERT_EQ(t.size(), 5u);
  ASSERT_EQ(f.size(), 15u);
  EXPECT_EQ(t[4], 4e-4);
  EXPECT_EQ(f[3 * 4 + 2], 100.0 + 40.0 + 2.0);
}

}  // namespace
}  // namespace crashlink::io
