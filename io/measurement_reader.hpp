#pragma once
// The measurement CSV reader with the rod count rule spelled out, for the
// set reader (io/measurement_sets.cpp), whose files must all have the rods
// of the first. Not part of the API: io/measurement_csv.hpp is.
#include <filesystem>
#include <string>

#include "io/measurement_csv.hpp"

namespace rigflex::io {

// What the rod count must be: `count` = 0 for any; `origin` says where the
// expectation comes from, for the message (" as in h1.csv").
struct RodRule {
  int count = 0;
  std::string origin;
};

rig::Record read_measurement_file(const std::filesystem::path& file, RodRule rule);

}  // namespace rigflex::io
