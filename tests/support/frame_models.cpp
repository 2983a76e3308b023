#include "support/frame_models.hpp"

#include <stdexcept>

#include "fe/dof.hpp"
#include "fe/meshers.hpp"
#include "fe/node_merger.hpp"

namespace rigflex::test {
namespace {

using fe::Vec3;

fe::BeamSection steel_section(const std::string& name, fe::SectionShape shape, double width = 0.0,
                              double height = 0.0) {
  fe::BeamSection s;
  s.name = name;
  s.material = "steel";
  s.shape = shape;
  s.width = width;
  s.height = height;
  return s;
}

}  // namespace

void fix(fe::Model& m, fe::NodeId node, std::initializer_list<int> dofs) {
  fe::DofMask mask{};
  for (int d : dofs) mask[static_cast<size_t>(d)] = true;
  m.supports.push_back({"s" + std::to_string(m.supports.size()), node, mask});
}

void fix_all_nodes(fe::Model& m, std::initializer_list<int> dofs) {
  for (const auto& n : m.nodes) fix(m, n.id, dofs);
}

void clamp(fe::Model& m, const std::string& id, fe::NodeId node) {
  m.supports.push_back({id, node, {true, true, true, true, true, true}});
}

fe::Model steel_model() {
  fe::Model m;
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850};
  return m;
}

fe::BeamSection tube_section(const std::string& name, double diameter, double wall) {
  fe::BeamSection s = steel_section(name, fe::SectionShape::Tube);
  s.diameter = diameter;
  s.wall = wall;
  return s;
}

fe::BeamSection rect_section(const std::string& name, double width, double height) {
  return steel_section(name, fe::SectionShape::Rectangle, width, height);
}

fe::BeamSection box_section(const std::string& name, double width, double height, double wall) {
  fe::BeamSection s = steel_section(name, fe::SectionShape::Box, width, height);
  s.wall = wall;
  return s;
}

fe::BeamSection box_section(const std::string& name, double width, double height, double web_thickness,
                            double flange_thickness) {
  fe::BeamSection s = steel_section(name, fe::SectionShape::Box, width, height);
  s.web_thickness = web_thickness;
  s.flange_thickness = flange_thickness;
  return s;
}

std::vector<fe::NodeId> member(fe::Model& m, fe::NodeMerger& merger, const std::string& id, const Vec3& from,
                               const Vec3& to, int elements, const std::string& section) {
  fe::MemberSpec s;
  s.id = id;
  s.from = from;
  s.to = to;
  s.elements = elements;
  s.section = section;
  return fe::mesh_member(m, merger, s);
}

fe::Spring axial_spring(const std::string& id, fe::NodeId a, std::optional<fe::NodeId> b, double k,
                        std::optional<Vec3> direction) {
  return {.id = id, .node = a, .other = b, .axial = k, .direction = direction};
}

fe::Spring grounded_spring(const std::string& id, fe::NodeId node, const std::array<double, 6>& stiffness) {
  fe::Spring s;
  s.id = id;
  s.node = node;
  s.stiffness = stiffness;
  return s;
}

fe::Model portal_frame(double beam_I, std::array<fe::NodeId, 2>* corners) {
  using enum fe::Dof;
  fe::Model m = steel_model();
  fe::BeamSection col;
  col.name = "col";
  col.material = "steel";
  col.A = 1e3;  // axially rigid, as the closed form assumes
  col.Iy = col.Iz = 1e-4;
  col.J = 1e-4;
  fe::BeamSection beam = col;
  beam.name = "beam";
  beam.Iy = beam.Iz = beam_I;
  m.beam_sections["col"] = col;
  m.beam_sections["beam"] = beam;
  fe::NodeMerger merger(m);
  auto member = [&](Vec3 a, Vec3 b, const std::string& sec) {
    fe::MemberSpec s;
    s.id = sec + std::to_string(m.beams.size());
    s.from = a;
    s.to = b;
    s.elements = 4;
    s.section = sec;
    s.theory = fe::BeamTheory::EulerBernoulli;
    s.mass = fe::MassKind::None;
    return fe::mesh_member(m, merger, s);
  };
  const auto c1 = member({0, 0, 0}, {0, 4, 0}, "col");
  const auto c2 = member({6, 0, 0}, {6, 4, 0}, "col");
  member({0, 4, 0}, {6, 4, 0}, "beam");
  const int ux = static_cast<int>(UX), uy = static_cast<int>(UY), uz = static_cast<int>(UZ);
  const int rx = static_cast<int>(RX), ry = static_cast<int>(RY), rz = static_cast<int>(RZ);
  fix(m, c1.front(), {ux, uy, rz});
  fix(m, c2.front(), {ux, uy, rz});
  fix_all_nodes(m, {uz, rx, ry});
  m.point_masses.push_back({"m1", c1.back(), 5000.0, {}});
  m.point_masses.push_back({"m2", c2.back(), 5000.0, {}});
  if (corners) *corners = {c1.back(), c2.back()};
  return m;
}

fe::Model rig_fixed_frame(int elements_per_member) {
  fe::Model m = steel_model();
  m.beam_sections["column"] = box_section("column", 0.2, 0.2, 0.01);
  m.beam_sections["cross"] = box_section("cross", 0.16, 0.3, 0.008);
  fe::FixedFrameSpec s;
  s.column_bases = {{-1.6, -1.4, 0.0}, {1.6, -1.4, 0.0}, {1.6, 1.4, 0.0}, {-1.6, 1.4, 0.0}};
  s.height = 3.2;
  s.column_section = "column";
  s.beam_section = "cross";
  s.joints = {{1.2, -1.4, 3.05}, {-1.2, -1.4, 3.05}, {0.0, 1.4, 3.05}};
  s.elements_per_member = elements_per_member;
  fe::build_fixed_frame(m, s);
  return m;
}

fe::Model rig_carrying_frame(int elements_per_member) {
  fe::Model m = steel_model();
  m.beam_sections["beam"] = box_section("beam", 0.12, 0.16, 0.006);
  fe::CarryingFrameSpec s;
  s.corner_min = {-1.5, -1.0, 0.0};
  s.corner_max = {1.5, 1.0, 0.0};
  s.bays_x = 2;
  s.bays_y = 1;
  s.section = "beam";
  s.joints = {{1.2, -1.0, 0.1}, {-1.2, -1.0, 0.1}, {0.0, 1.0, 0.1}};
  s.elements_per_member = elements_per_member;
  fe::build_carrying_frame(m, s);
  fe::NodeMerger merger(m);
  const auto centre = merger.find({0.0, 0.0, 0.0});
  if (!centre) throw std::invalid_argument("rig_carrying_frame: elements_per_member must be even");
  m.point_masses.push_back({"payload", *centre, 400.0, {60.0, 90.0, 140.0, 2.0, -3.0, 1.5}});
  return m;
}

fe::PatchNodes clamped_plate(fe::Model& m, double length, double width, double thickness, int nx, int ny,
                             bool quadratic) {
  m.shell_sections["plate"] = {"plate", "steel", thickness};
  fe::NodeMerger merger(m);
  fe::PatchSpec p;
  p.id = "plate";
  p.corners = {fe::Vec3(0, 0, 0), fe::Vec3(length, 0, 0), fe::Vec3(length, width, 0), fe::Vec3(0, width, 0)};
  p.nx = nx;
  p.ny = ny;
  p.quadratic = quadratic;
  p.section = "plate";
  const fe::PatchNodes g = fe::mesh_shell_patch(m, merger, p);
  for (int r = 0; r < g.rows; ++r) {
    if (g.at(r, 0) != 0)
      m.supports.push_back({"root" + std::to_string(r), g.at(r, 0), {true, true, true, true, true, true}});
  }
  return g;
}

}  // namespace rigflex::test
