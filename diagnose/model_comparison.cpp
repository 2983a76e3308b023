#include "diagnose/model_comparison.hpp"

#include <cstdio>
#include <memory>
#include <mutex>

#include "identify/identification_kinematics.hpp"
#include "identify/identification_rig.hpp"
#include "rig/parallel_for.hpp"

namespace rigflex::diagnose {

namespace {

ModelComparison compare_as_given(const ResponseModel& m, const std::vector<const rig::Record*>& records,
                                 const std::vector<std::string>& sources, const ModelComparisonOptions& options) {
  const int H = static_cast<int>(records.size());
  const int n = m.system.rods();
  ModelComparison c;
  c.channels = channel_names(n);
  c.histories.resize(records.size());
  std::mutex progress;
  int done = 0;
  rig::parallel_for(H, options.threads, [&](int j) {
    const std::string source = j < static_cast<int>(sources.size()) ? sources[j] : "history " + std::to_string(j + 1);
    try {
      c.histories[j] = compare_history(m, *records[j], source, options.compare);
    } catch (rig::RecordError& e) {
      e.set_history(j);
      throw;
    }
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress);
      options.progress(++done, H);
    }
  });
  c.nrmse = pooled_nrmse(c.histories);
  c.overall_nrmse = rms_of(c.nrmse, 0, 3 * n);
  c.force_nrmse = rms_of(c.nrmse, 0, n);
  c.angle_nrmse = rms_of(c.nrmse, n, 2 * n);
  c.raw_nrmse = pooled_nrmse(c.histories, true);
  c.raw_overall_nrmse = rms_of(c.raw_nrmse, 0, 3 * n);
  c.raw_force_nrmse = rms_of(c.raw_nrmse, 0, n);
  c.analysis = analyse_residuals(m, c.histories);

  for (const auto& h : c.histories) {
    if (h.fit_window_nrmse > kFollowLimit) {
      char figures[64];
      std::snprintf(figures, sizeof figures, "NRMSE %.2f over the first %.1f s", h.fit_window_nrmse,
                    options.compare.fit_window_s);
      c.warnings.push_back(h.source + ": the model does not follow the data from the start (" + figures +
                           "): check the rod order and encoder axes against the rig file, the units (N, rad, s), "
                           "that the record starts after release, and run `rigflex diagnose` for a large missing "
                           "effect");
    }
    if (!h.fit.converged) {
      c.warnings.push_back(h.source + ": the swing state fit did not converge");
    }
  }

  return c;
}

// The mass properties from the records with the model's algorithm.
void identify_with(const ResponseModel& m, const std::vector<const rig::Record*>& records, ModelComparison& c) {
  const bool flexible = m.system.assembly().fixed_frame || m.system.assembly().carrying_frame ||
                        !m.system.assembly().rod_stiffness.empty();
  c.algorithm = flexible ? identify::IdentificationAlgorithm::flexible : identify::IdentificationAlgorithm::rigid;
  try {
    const identify::IdentificationRig idr = identify::identification_rig(m.system.model(), c.algorithm);
    identify::IdentificationResult r = identify::identify(idr, records, {});
    if (r.observable) {
      c.identified = std::move(r);
    } else {
      c.identification_error = r.message;
    }
  } catch (const rig::RecordError&) {
    throw;
  } catch (const std::exception& e) {
    c.identification_error = e.what();
  }
}

}  // namespace

ModelComparison compare_model(const ResponseModel& m, const std::vector<const rig::Record*>& records,
                              const std::vector<std::string>& sources, const ModelComparisonOptions& options) {
  options.compare.validate();
  if (records.empty()) throw std::invalid_argument("compare needs at least one history");
  ModelComparison c = compare_as_given(m, records, sources, options);
  // The identification does not use the body; it does use refitted rods and effects.
  std::unique_ptr<const ResponseModel> refitted;
  if (options.fit_model) {
    if (auto fit = fit_model_parameters(m, c.histories, {options.compare, options.threads, options.fit_progress})) {
      if (fit->credible) {
        if (options.fit_progress) options.fit_progress("comparing the model with its parameters refitted");
        refitted = std::make_unique<const ResponseModel>(fit->model);
        const ModelComparison::Nrmse as_stated{c.overall_nrmse, c.force_nrmse, c.angle_nrmse};
        c = compare_as_given(*refitted, records, sources, options);
        c.as_stated = as_stated;
      }
      c.model_fit = std::move(fit);
    }
  }
  if (options.identify) identify_with(refitted ? *refitted : m, records, c);
  return c;
}

}  // namespace rigflex::diagnose
