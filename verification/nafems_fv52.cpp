#include "verification/nafems_fv52.hpp"

#include <cmath>

#include "fe/meshers.hpp"

namespace rigflex::verification {

fe::Model nafems_fv52(const std::string& element, int n, int nz) {
  fe::Model m;
  m.materials["steel"] = fe::Material{"steel", 2.0e11, 0.3, 8000.0};
  fe::NodeMerger merger(m);
  fe::SolidBlockSpec spec;
  spec.id = "plate";
  spec.corners = {fe::Vec3(0, 0, 0), fe::Vec3(10, 0, 0), fe::Vec3(10, 10, 0), fe::Vec3(0, 10, 0),
                  fe::Vec3(0, 0, 1), fe::Vec3(10, 0, 1), fe::Vec3(10, 10, 1), fe::Vec3(0, 10, 1)};
  spec.nx = spec.ny = n;
  spec.nz = nz;
  spec.element = element;
  spec.material = "steel";
  fe::mesh_solid_block(m, merger, spec);
  auto at = [](double v, double c) { return std::abs(v - c) < 1e-9; };
  for (const fe::Node& node : m.nodes) {
    const fe::Vec3& x = node.x;
    const bool edge = at(x.x(), 0) || at(x.x(), 10) || at(x.y(), 0) || at(x.y(), 10);
    if (edge && at(x.z(), 0)) m.supports.push_back({"edge", node.id, {false, false, true, false, false, false}});
  }
  return m;
}

}  // namespace rigflex::verification
