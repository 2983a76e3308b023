#include "report/identify_sets.hpp"

#include <iterator>
#include <mutex>

#include "identify/identification_rig.hpp"
#include "rig/parallel_for.hpp"

namespace rigflex::report {

void IdentifySetsOptions::validate() const {
  algorithms_of(algorithm);
  if (threads < 0) throw std::invalid_argument("threads: must be >= 0 (0: every core)");
}

std::vector<identify::IdentificationAlgorithm> algorithms_of(const std::string& choice) {
  using A = identify::IdentificationAlgorithm;
  if (choice == "rigid") return {A::rigid};
  if (choice == "flexible") return {A::flexible};
  if (choice == "both") return {A::rigid, A::flexible};
  throw std::invalid_argument("algorithm: expected rigid, flexible or both, not '" + choice + "'");
}

void identify_sets(const rig::RigModel& model, const std::vector<std::vector<const rig::Record*>>& sets,
                   const IdentifySetsOptions& options, IdentificationReport& report) {
  options.validate();
  if (report.set_files.size() != sets.size()) {
    throw std::invalid_argument("identify_sets: one list of file names per set expected");
  }
  const int n = static_cast<int>(sets.size());
  for (const auto alg : algorithms_of(options.algorithm)) {
    const identify::IdentificationRig rig = identify::identification_rig(model, alg);
    std::vector<identify::IdentificationResult> results(sets.size());
    std::vector<std::vector<IdentificationReport::Test>> tests(sets.size());
    std::mutex progress;
    int done = 0;
    rig::parallel_for(n, options.threads, [&](int k) {
      const auto set = static_cast<std::size_t>(k);
      try {
        results[set] = identify::identify(rig, sets[set], report.options);
      } catch (const rig::RecordError& e) {
        throw SetError(set, e.what(), e);
      }
      if (!results[set].observable) throw SetError(set, results[set].message);
      tests[set] = identify_tests(rig, sets[set], report.set_files[set], set, report.options);
      if (options.progress) {
        std::lock_guard<std::mutex> lock(progress);
        options.progress(alg, ++done, n);
      }
    });
    std::vector<IdentificationReport::Test> all;
    for (auto& t : tests) std::move(t.begin(), t.end(), std::back_inserter(all));
    report.add(alg, std::move(results), std::move(all));
  }
}

}  // namespace rigflex::report
