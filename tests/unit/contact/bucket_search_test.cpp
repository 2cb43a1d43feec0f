// The bucket search returns exactly the pairs of the brute-force reference (same predicate:
// node inside the segment's node box inflated by its reach) on random meshes: random quads and
// triangles of random sizes, random slave clouds, flat (plate-like) and 3-D clouds.
#include "solver/contact/bucket_search.h"

#include <gtest/gtest.h>

#include <random>

using namespace crashlink::contact;

namespace {

struct RandomScene {
  std::vector<double> x;
  std::vector<std::int32_t> slaves, seg_nodes;
  std::vector<double> reach;
};

RandomScene make_scene(unsigned seed, std::size_t nseg, std::size_t nslave, bool flat) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomScene s;
  auto add_node = [&](double a, double b, double c) {
    s.x.insert(s.x.end(), {a, b, c});
    return static_cast<std::int32_t>(s.x.size() / 3 - 1);
  };
  for (std::size_t i = 0; i < nseg; ++i) {
    const double cx = u(rng), cy = u(rng), cz = flat ? 0.01 * u(rng) : u(rng);
    const double size = 0.005 + 0.05 * u(rng) * u(rng);  // sizes spread over a decade
    std::int32_t q[4];
    for (int a = 0; a < 4; ++a)
      q[a] = add_node(cx + size * (u(rng) - 0.5), cy + size * (u(rng) - 0.5),
                      cz + size * (u(rng) - 0.5));
    if (i % 5 == 0) q[3] = q[2];  // triangles
    s.seg_nodes.insert(s.seg_nodes.end(), q, q + 4);
    s.reach.push_back(0.002 + 0.01 * u(rng));
  }
  for (std::size_t k = 0; k < nslave; ++k)
    s.slaves.push_back(add_node(u(rng), u(rng), flat ? 0.01 * u(rng) : u(rng)));
  return s;
}

void expect_identical(const RandomScene& s) {
  const SearchInput in{s.x.data(),         s.slaves.data(), s.slaves.size(),
                       s.seg_nodes.data(), s.reach.data(),  s.reach.size()};
  CandidateList fast, ref;
  BucketWork w;
  bucket_search(in, fast, w);
  brute_force_search(in, ref);
  ASSERT_GT(ref.pairs(), 0u);  // the scene must exercise something
  EXPECT_EQ(fast.offset, ref.offset);
  EXPECT_EQ(fast.segment, ref.segment);
  // A second call with warm buffers gives the same answer.
  CandidateList again;
  bucket_search(in, again, w);
  EXPECT_EQ(again.segment, ref.segment);
}

}  // namespace

TEST(BucketSearch, IdenticalToBruteForceOn3dClouds) {
  for (unsigned seed = 1; seed <= 5; ++seed) expect_identical(make_scene(seed, 2000, 3000, false));
}

TEST(BucketSearch, IdenticalToBruteForceOnFlatClouds) {
  for (unsigned seed = 11; seed <= 15; ++seed) expect_identical(make_scene(seed, 3000, 3000, true));
}

TEST(BucketSearch, SparseCloudKeepsGridBoundedAndExact) {
  // Two distant clusters: the grid would be huge at the segment size; the cell is enlarged.
  RandomScene s = make_scene(21, 500, 500, false);
  for (std::size_t k = 0; k < 250; ++k) s.x[3 * static_cast<std::size_t>(s.slaves[k])] += 1000.0;
  expect_identical(s);
}
