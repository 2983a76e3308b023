#pragma once
// Every measurement set identified with each algorithm chosen, and every
// history of a set alone (the tests), into an IdentificationReport: the work
// of `rigflex identify` and of the Python module's `identify`, which differ
// only in how they name a set that fails.
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "identify/identification.hpp"
#include "report/identification_report.hpp"
#include "rig/record.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::report {

// A set that cannot be identified: one of its records the rig cannot have
// produced (`record`), or a motion that leaves a mass property unobservable.
class SetError : public std::invalid_argument {
 public:
  SetError(std::size_t set, const std::string& message, std::optional<rig::RecordError> record = std::nullopt)
      : std::invalid_argument(message), set_(set), record_(std::move(record)) {}
  std::size_t set() const { return set_; }
  const std::optional<rig::RecordError>& record() const { return record_; }

 private:
  std::size_t set_;
  std::optional<rig::RecordError> record_;
};

struct IdentifySetsOptions {
  std::string algorithm = "rigid";  // rigid, flexible or both (rigid first)
  int threads = 1;                  // sets identified at once; 0: every core
  // After each set, serialized: the algorithm, sets done, sets in all.
  std::function<void(identify::IdentificationAlgorithm, int, int)> progress;
  void validate() const;  // std::invalid_argument naming the field
};

// rigid -> {rigid}, flexible -> {flexible}, both -> {rigid, flexible}.
std::vector<identify::IdentificationAlgorithm> algorithms_of(const std::string& choice);

// Identifies `sets` (a set: its histories) with report.options and adds each
// algorithm's results and tests to `report`, whose set_files name the
// histories (one list per set). Throws SetError for a set that cannot be
// identified.
void identify_sets(const rig::RigModel& model, const std::vector<std::vector<const rig::Record*>>& sets,
                   const IdentifySetsOptions& options, IdentificationReport& report);

}  // namespace rigflex::report
