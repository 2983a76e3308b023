// report::identify_sets' contract (its work is tested end to end through
// `rigflex identify`, tests/apps/test_cli_identify.cpp, and the Python
// module's identify, python/tests): the algorithm choice, the options'
// validation, the file names it needs per set.
#include <gtest/gtest.h>

#include <stdexcept>

#include "report/identify_sets.hpp"

namespace rigflex {
namespace {

using A = identify::IdentificationAlgorithm;

TEST(IdentifySets, TheChoiceGivesTheAlgorithmsRigidFirst) {
  EXPECT_EQ(report::algorithms_of("rigid"), std::vector<A>{A::rigid});
  EXPECT_EQ(report::algorithms_of("flexible"), std::vector<A>{A::flexible});
  EXPECT_EQ(report::algorithms_of("both"), (std::vector<A>{A::rigid, A::flexible}));
  EXPECT_THROW(report::algorithms_of("Rigid"), std::invalid_argument);
}

TEST(IdentifySets, OptionsAreValidatedBeforeAnyWork) {
  report::IdentifySetsOptions o;
  EXPECT_NO_THROW(o.validate());
  o.threads = -1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.threads = 0;
  o.algorithm = "all";
  try {
    o.validate();
    FAIL() << "an unknown algorithm was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("algorithm"), std::string::npos) << e.what();
  }
}

TEST(IdentifySets, EverySetNeedsItsFileNames) {
  report::IdentificationReport rep;  // no set_files for the one set given
  const std::vector<std::vector<const rig::Record*>> sets(1);
  EXPECT_THROW(report::identify_sets(rig::RigModel{}, sets, {}, rep), std::invalid_argument);
  EXPECT_TRUE(rep.algorithms.empty());
}

TEST(IdentifySets, ASetErrorKeepsTheSetAndTheRecordError) {
  const rig::RecordError record(2000, "alpha1", "rod 1 above its joint");
  const report::SetError e(3, record.what(), record);
  EXPECT_EQ(e.set(), 3u);
  ASSERT_TRUE(e.record().has_value());
  EXPECT_EQ(e.record()->sample(), 2000);
  EXPECT_EQ(e.record()->channel(), "alpha1");
  EXPECT_FALSE(report::SetError(0, "zG not observable").record().has_value());
}

}  // namespace
}  // namespace rigflex
