#pragma once
// The HTML reports of rigflex's commands (docs/reports.md): pure builders
// from a command's results to an report::HtmlReport, which the caller writes
// (HtmlReport::write: atomic). Nothing is printed; text is escaped by
// HtmlReport; series are passed whole (HtmlReport decimates them for display).
// Non-finite values are gaps in plots and "–" in tables. The builders throw
// std::invalid_argument, naming the field, only for data that contradict
// themselves (a matrix whose size does not match the channels, series of
// different lengths).
//
// Plots (HtmlReport::plot_count) per report:
//  compare_report        per channel group (forces F1..Fn; angles alpha, beta)
//                        of the first history: measured and model (2), residual
//                        (2), when there is a history and channels; residual
//                        spectra with the measured spectrum (2: forces, angles)
//                        when analysis.spectra has frequencies; NRMSE trend (1)
//                        when analysis.trend_t is not empty; decay rates (1)
//                        when analysis.decay is not empty; error by model
//                        version (1) when `study` is not empty. At most 9.
//  diagnosis_report      effect ranking (1) when d.ranking is not empty;
//                        residuals of the first baseline history (2) when
//                        there is one; with `baseline_analysis`, its spectra
//                        (2), trend (1) and decay (1) as in compare_report.
//  identification_html   normal-probability plot of the CoG height, one per
//                        algorithm with a set of finite zG (none when the
//                        static procedure imposes the whole CoG).
//  sweep_html            zG error and Jyy error against f1 (2) when some
//                        point has an f1.
#include <string>
#include <vector>

#include "report/compare_json.hpp"
#include "report/html_report.hpp"
#include "report/identification_report.hpp"
#include "report/study.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/model_comparison.hpp"
#include "diagnose/residual_analysis.hpp"
#include "identify/sweep.hpp"

namespace rigflex::report {

// `rigflex compare`: summary and per-channel errors, warnings, per history
// table; measured vs model and residuals of the first history; residual and
// measured spectra with the model's modes as markers; NRMSE trend; decay
// rates; state correlations; largest residual windows; error by model
// version (study entries, labelled "v1 rig.yaml", ...); identified mass
// properties against ctx.reference.
HtmlReport compare_report(const diagnose::ModelComparison& c, const CompareContext& ctx,
                          const std::vector<StudyEntry>& study);

// `rigflex diagnose`: verdict, ranking by explained share (significant
// effects marked "name *"), fitted parameters, advice and rig-file block of
// the missing effect, the baseline per history and its residuals. The
// diagnosis holds no residual analysis (analyse_residuals needs the model):
// pass diagnose::analyse_residuals(ResponseModel(model), d.baseline) as
// `baseline_analysis` for spectra with mode markers, trend and decay.
HtmlReport diagnosis_report(const diagnose::Diagnosis& d, const CompareContext& ctx,
                            const diagnose::ResidualAnalysis* baseline_analysis = nullptr);

// `rigflex identify`: per algorithm the sets' mass properties with mean and
// standard deviation, mean against the reference and the share inside the
// rig's accuracy, rigid against flexible (Welch) when both ran; normal-
// probability plot of the CoG height differences: zG minus the static zG
// (tare taken out, as in identification.json; not with a fully imposed CoG),
// else minus the reference zG, else minus the algorithm's mean zG.
HtmlReport identification_html(const IdentificationReport& r);

// `rigflex sweep`: zG error (mm) and Jyy error (%) of the rigid and the
// flexible algorithm against f1 (log axis), one curve per algorithm and sweep
// kind, with markers at 3 and 4 times the highest swing frequency (median
// over the points); table of every point with its failure.
HtmlReport sweep_html(const std::string& rig, const std::vector<identify::SweepPoint>& points);

}  // namespace rigflex::report
