#include "diagnose/body_parameters.hpp"

#include <array>

namespace rigflex::diagnose {

namespace {
const std::array<const char*, 9> kNames{"cog_x", "cog_y", "cog_z", "Jxx", "Jyy", "Jzz", "Jxy", "Jxz", "Jyz"};
}

BodyParameters body_parameters(const rig::RigModel& model) {
  const auto Jstd = model.body_uncertainty.inertia_std(model.body);
  std::array<double, 9> sigma{};
  for (int k = 0; k < 3; ++k) sigma[k] = model.body_uncertainty.cog(k);
  for (int k = 0; k < 6; ++k) sigma[3 + k] = Jstd[k];
  // Probes: small against the prior (the responses are smooth in the mass
  // properties) yet far above the simulator's round-off: 0.2 mm of CoG and
  // 0.2 % of the mean principal moment move the swing-band forces by
  // several times their noise on the test rigs.
  const double moment = model.body.inertia.trace() / 3.0;
  BodyParameters p;
  std::vector<double> s;
  for (int k = 0; k < 9; ++k) {
    if (!(sigma[k] > 0)) continue;
    p.components.push_back(k);
    rig::FitParameter f;
    f.name = kNames[k];
    f.unit = k < 3 ? "m" : "kg m^2";
    f.probe = k < 3 ? 2e-4 : 2e-3 * moment;
    f.low = -3 * sigma[k];
    f.high = 3 * sigma[k];
    p.parameters.push_back(f);
    s.push_back(sigma[k]);
  }
  p.sigma = Eigen::Map<const Eigen::VectorXd>(s.data(), static_cast<Eigen::Index>(s.size()));
  return p;
}

fe::MassProperties body_with(const fe::MassProperties& body, const BodyParameters& p, const Eigen::VectorXd& delta) {
  fe::MassProperties out = body;
  std::array<double, 6> J = rig::inertia_components(body.inertia);
  for (int i = 0; i < p.size(); ++i) {
    const int k = p.components[i];
    if (k < 3) {
      out.cog(k) += delta(i);
    } else {
      J[k - 3] += delta(i);
    }
  }
  out.inertia = rig::inertia_tensor(J);
  return out;
}

}  // namespace rigflex::diagnose
