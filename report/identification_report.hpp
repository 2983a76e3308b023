#pragma once
// The results of `rigflex identify` over one or more measurement sets, as
// DIR/identification.json and as a printed table: per set the spec's mass
// properties record with the checks of the solve, over the sets mean,
// standard deviation and confidence interval; against a reference the errors,
// the share inside the rig's accuracy and normal-probability data of the CoG
// height; rigid against flexible by Welch's t-test when both ran.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fe/mass_properties.hpp"
#include "identify/identification.hpp"
#include "identify/mass_statistics.hpp"

namespace rigflex::report {

struct IdentificationReport {
  std::string rig;
  std::vector<std::string> set_names;
  std::vector<std::vector<std::string>> set_files;
  identify::IdentificationOptions options;
  std::optional<fe::MassProperties> tare;       // subtracted from every set
  std::optional<fe::MassProperties> reference;  // errors and accuracy against it
  std::optional<double> static_cog_height;      // zG of the static procedure (m)
  identify::AccuracyLimits limits;

  // One history (a test: one push and free swing) identified alone.
  struct Test {
    std::size_t set = 0;  // index into set_names
    std::string file;
    identify::IdentificationResult result;  // of the system on the rods
    fe::MassProperties record;              // tare subtracted when given; when result.observable
  };
  struct Algorithm {
    identify::IdentificationAlgorithm algorithm;
    std::vector<identify::IdentificationResult> results;  // per set, of the system on the rods
    std::vector<fe::MassProperties> records;         // per set, tare subtracted when given
    std::vector<Test> tests;                         // every history alone, in set order (sets of two or more)
  };
  std::vector<Algorithm> algorithms;

  // Adds one algorithm's results (one per set, in set order) and, optionally,
  // its tests (`record` is filled here).
  void add(identify::IdentificationAlgorithm a, std::vector<identify::IdentificationResult> results,
           std::vector<Test> tests = {});

  nlohmann::ordered_json json() const;
  std::string table() const;
};

// Each history of a set of two or more identified alone (a test; set `index`,
// files[i] naming histories[i]): the test-to-test scatter. A history that
// does not determine the unknowns alone (one push excites too little), or
// that the identification refuses alone, is kept as not observable with the
// reason; the set's own solve decides what is bad input. A set of one
// history has no tests.
std::vector<IdentificationReport::Test> identify_tests(const identify::IdentificationRig& rig,
                                                       const std::vector<const rig::Record*>& histories,
                                                       const std::vector<std::string>& files, std::size_t index,
                                                       const identify::IdentificationOptions& options);

// The CoG heights a normal probability plot shows: every test's (each
// history identified alone) where that gives more values than the sets and at
// least two, else every set's; `of` says which ("tests" or "sets"). Non-finite
// heights are left out.
struct HeightSample {
  std::vector<double> z;  // m
  std::string of;
};
HeightSample height_sample(const IdentificationReport::Algorithm& a);

}  // namespace rigflex::report
