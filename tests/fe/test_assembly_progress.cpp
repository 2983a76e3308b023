// Assembly reports its progress: counts that rise to the number of
// elements, and the same matrices as without a listener.
#include <gtest/gtest.h>

#include <vector>

#include "fe/assembly.hpp"
#include "fe/element_loop.hpp"
#include "support/frame_models.hpp"

namespace rigflex {
namespace {

TEST(AssemblyProgress, CountsRiseToEveryElementAndChangeNothing) {
  const fe::Model m = test::rig_fixed_frame(40);
  const long elements = fe::element_count(m);
  ASSERT_GT(elements, 100);  // every 2 % step holds an element
  std::vector<long> seen;
  fe::AssemblyOptions o;
  o.progress = [&](long done, long total) {
    EXPECT_EQ(total, elements);
    seen.push_back(done);
  };
  const fe::AssembledSystem with = fe::assemble(m, o);
  ASSERT_EQ(seen.size(), 50u);  // one per 2 %, not one per element
  for (size_t k = 1; k < seen.size(); ++k) EXPECT_GT(seen[k], seen[k - 1]);
  EXPECT_EQ(seen.back(), elements);
  const fe::AssembledSystem without = fe::assemble(m);
  EXPECT_EQ((with.K - without.K).norm(), 0.0);
  EXPECT_EQ((with.M - without.M).norm(), 0.0);
}

}  // namespace
}  // namespace rigflex
