#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "io/atomic_file.hpp"
#include "io/measurement_csv.hpp"
#include "io/measurement_text.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;
using namespace measurement_text;

[[noreturn]] void refuse_history(const std::string& what) { throw std::invalid_argument("time history: " + what); }

void check_sizes(const rig::Record& h) {
  const Eigen::Index n = h.force.cols(), rows = h.t.size();
  if (rows == 0) refuse_history("no samples");
  if (n == 0) refuse_history("no rods (force has no columns)");
  for (const auto& [A, name] : {std::pair<const Eigen::MatrixXd*, const char*>{&h.force, "force"},
                                {&h.alpha, "alpha"},
                                {&h.beta, "beta"}})
    if (A->rows() != rows || A->cols() != n)
      refuse_history(std::string(name) + " is " + std::to_string(A->rows()) + " x " + std::to_string(A->cols()) +
             ", expected " + std::to_string(rows) + " x " + std::to_string(n) + " (samples x rods)");
}

void check_values(const rig::Record& h) {
  auto sample = [](Eigen::Index i) { return " of sample " + std::to_string(i + 1); };
  for (Eigen::Index i = 0; i < h.t.size(); ++i) {
    if (!std::isfinite(h.t(i))) refuse_history("t" + sample(i) + " is " + number_text(h.t(i)));
    if (i > 0 && !(h.t(i) > h.t(i - 1)))
      refuse_history("t" + sample(i) + " (" + number_text(h.t(i)) + ") is not after the previous sample's (" +
             number_text(h.t(i - 1)) + "): time must strictly increase");
  }
  for (const auto& [A, q] : {std::pair<const Eigen::MatrixXd*, Quantity>{&h.force, Quantity::force},
                             {&h.alpha, Quantity::alpha},
                             {&h.beta, Quantity::beta}})
    for (Eigen::Index k = 0; k < A->cols(); ++k)
      for (Eigen::Index i = 0; i < A->rows(); ++i)
        if (!std::isfinite((*A)(i, k)))
          refuse_history(column_name(q, static_cast<int>(k + 1)) + sample(i) + " is " + number_text((*A)(i, k)));
}

// Each comment must come back from its "# key: value" line as itself.
void check_comments(const rig::Record& h) {
  for (const auto& [key, value] : h.provenance.comments) {
    const std::string which = "comment '" + key + "'";
    if (key.empty()) refuse_history("a comment has an empty key");
    if (key.find(':') != std::string::npos) refuse_history(which + ": the key contains ':'");
    for (const std::string* s : {&key, &value}) {
      if (s->find_first_of("\r\n") != std::string::npos) refuse_history(which + ": a line break in the key or value");
      if (trim(*s) != *s) refuse_history(which + ": blanks at the start or end of the key or value");
      if (!valid_utf8(*s)) refuse_history(which + ": not valid UTF-8");
    }
  }
}

}  // namespace

std::string format_record_csv(const rig::Record& h) {
  check_sizes(h);
  check_values(h);
  check_comments(h);
  const Eigen::Index n = h.force.cols();
  std::string out;
  out.reserve(static_cast<size_t>(h.t.size() * (3 * n + 1) * 24 + 256));
  // "# key:" for an empty value: no trailing blank.
  for (const auto& [key, value] : h.provenance.comments)
    out.append("# ").append(key).append(value.empty() ? ":" : ": ").append(value).append("\n");
  out.append("t");
  for (Eigen::Index k = 1; k <= n; ++k) out.append(",F").append(std::to_string(k));
  for (Eigen::Index k = 1; k <= n; ++k)
    out.append(",alpha").append(std::to_string(k)).append(",beta").append(std::to_string(k));
  out.append("\n");
  for (Eigen::Index i = 0; i < h.t.size(); ++i) {
    append_number(out, h.t(i));
    for (Eigen::Index k = 0; k < n; ++k) append_number(out.append(","), h.force(i, k));
    for (Eigen::Index k = 0; k < n; ++k) {
      append_number(out.append(","), h.alpha(i, k));
      append_number(out.append(","), h.beta(i, k));
    }
    out.append("\n");
  }
  return out;
}

void write_record_csv(const fs::path& file, const rig::Record& h) {
  // Formatted (and so checked) before anything touches the disk.
  write_text_atomically(file, format_record_csv(h));
}

}  // namespace rigflex::io
