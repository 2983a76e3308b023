#pragma once
// The CalculiX tests skip, saying what, where ccx is not installed
// (scripts/install-deps.sh installs it; CI always has it).
#include <gtest/gtest.h>

#include "verification/calculix.hpp"

#define REQUIRE_CCX(what)                                \
  if (!rigflex::verification::calculix_available("ccx")) \
  GTEST_SKIP() << "CalculiX (ccx) is not on PATH; " what " skipped"
