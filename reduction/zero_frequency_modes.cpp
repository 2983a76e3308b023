#include "reduction/zero_frequency_modes.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "fe/bounding_box.hpp"
#include "linalg/pencil_scale.hpp"

namespace rigflex::reduction {
namespace {

// The diagonal of the model's bounding box: a length that turns a rotation
// into the displacement it causes across the model.
double model_size(const fe::Model& model) {
  const double d = fe::bounding_box_sides(model).norm();
  return d > 0 ? d : 1.0;
}

}  // namespace

bool is_supported(const fe::Model& model) {
  if (!model.supports.empty()) return true;
  return std::any_of(model.springs.begin(), model.springs.end(), [](const fe::Spring& s) { return !s.other; });
}

std::vector<ZeroFrequencyMode> zero_frequency_modes(const fe::Model& model, const ModalAnalysis& a, double share) {
  std::vector<ZeroFrequencyMode> out;
  const auto& r = a.result;
  if (r.eigenvalues.size() == 0) return out;
  const double limit = share * linalg::pencil_scale(a.system.K, a.system.M);
  const double L = model_size(model);
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    if (!(std::abs(r.eigenvalues(k)) <= limit)) continue;
    ZeroFrequencyMode z;
    z.mode = k;
    z.frequency_hz = a.summary.frequencies_hz.size() > k ? a.summary.frequencies_hz(k) : 0.0;
    Eigen::VectorXd amp = r.vectors.col(k).cwiseAbs();
    for (Eigen::Index i = 0; i < amp.size(); ++i) {
      if (a.system.dofs.local[static_cast<size_t>(i)] >= 3) amp(i) *= L;
    }
    const double top = amp.maxCoeff();
    std::vector<Eigen::Index> order(static_cast<size_t>(amp.size()));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index x, Eigen::Index y) { return amp(x) > amp(y); });
    for (Eigen::Index i : order) {
      if (!(amp(i) > 0.1 * top)) break;
      ++z.moving;
      if (z.largest.size() < kListed) z.largest.push_back(a.system.dofs.describe(i));
      const fe::NodeId node = a.system.dofs.node[static_cast<size_t>(i)];
      if (std::find(z.nodes.begin(), z.nodes.end(), node) == z.nodes.end()) z.nodes.push_back(node);
    }
    out.push_back(std::move(z));
  }
  return out;
}

}  // namespace rigflex::reduction
