#pragma once
// The models of the eigen benchmarks beyond the clamped plate (plate_model.hpp):
// 8-node plates, a shell box girder, a 3D beam lattice and a beam ladder, by
// "kind:size" (bench_block_size --models, bench_plate_modes --model).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/plate_model.hpp"
#include "fe/meshers.hpp"
#include "fe/model.hpp"
#include "fe/node_merger.hpp"

namespace rigflex::bench {

inline void add_steel_tube(fe::Model& m) {
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850.0};
  fe::BeamSection s;
  s.name = "tube";
  s.material = "steel";
  s.shape = fe::SectionShape::Box;
  s.width = 0.1;
  s.height = 0.1;
  s.wall = 0.005;
  m.beam_sections["tube"] = s;
}

inline void clamp(fe::Model& m, fe::NodeId node) {
  m.supports.push_back({"clamp", node, {true, true, true, true, true, true}});
}

// k x k x k nodes 0.5 m apart joined by one beam per edge along x, y and z;
// the bottom layer clamped.
inline fe::Model beam_lattice(int k) {
  fe::Model m;
  add_steel_tube(m);
  fe::NodeMerger merger(m);
  const double h = 0.5;
  auto member = [&](const fe::Vec3& a, const fe::Vec3& b) {
    fe::MemberSpec s;
    s.id = "bar";
    s.from = a;
    s.to = b;
    s.section = "tube";
    s.orientation = (b - a).normalized().cross(fe::Vec3::UnitX()).norm() > 0.5 ? fe::Vec3::UnitX() : fe::Vec3::UnitY();
    return fe::mesh_member(m, merger, s);
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        const fe::Vec3 p(i * h, j * h, l * h);
        if (i + 1 < k) member(p, p + fe::Vec3(h, 0, 0));
        if (j + 1 < k) member(p, p + fe::Vec3(0, h, 0));
        if (l + 1 < k) {
          const std::vector<fe::NodeId> ids = member(p, p + fe::Vec3(0, 0, h));
          if (l == 0) clamp(m, ids.front());
        }
      }
  return m;
}

inline fe::MemberSpec ladder_member(const fe::Vec3& from, const fe::Vec3& to) {
  fe::MemberSpec s;
  s.id = "ladder";
  s.from = from;
  s.to = to;
  s.elements = 4;
  s.section = "tube";
  s.orientation = fe::Vec3::UnitZ();
  return s;
}

// Two parallel rails 1 m apart with a rung every metre, 4 elements per rail
// bay and per rung, clamped at one end: a long, banded structure.
inline fe::Model beam_ladder(int bays) {
  fe::Model m;
  add_steel_tube(m);
  fe::NodeMerger merger(m);
  for (int b = 0; b <= bays; ++b) {
    const fe::Vec3 left(b, 0, 0), right(b, 1, 0);
    const std::vector<fe::NodeId> ids = fe::mesh_member(m, merger, ladder_member(left, right));
    if (b == 0) clamp(m, ids.front()), clamp(m, ids.back());
    if (b == bays) break;
    for (const double y : {0.0, 1.0}) {
      fe::mesh_member(m, merger, ladder_member(fe::Vec3(b, y, 0), fe::Vec3(b + 1, y, 0)));
    }
  }
  return m;
}

// A 0.4 m x 0.6 m box girder of 8 mm shells, 8 x 8 elements around the
// section, `along` elements over 10 m, clamped at one end through its
// reference node: the closed shell section rig frames are built from.
inline fe::Model shell_girder(int along) {
  fe::Model m;
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850.0};
  fe::NodeMerger merger(m);
  fe::BoxGirderSpec g;
  g.id = "girder";
  g.from = fe::Vec3(0, 0, 0);
  g.to = fe::Vec3(10, 0, 0);
  g.width = 0.4;
  g.height = 0.6;
  g.web_thickness = g.flange_thickness = 0.008;
  g.material = "steel";
  g.n_along = along;
  g.n_width = g.n_height = 8;
  const fe::BoxGirderNodes ends = fe::mesh_box_girder(m, merger, g);
  clamp(m, *ends.start_reference);
  return m;
}

// kind:size -> a model of about `size` DOFs.
inline fe::Model model_of(const std::string& spec, std::string& kind) {
  const size_t colon = spec.find(':');
  if (colon == std::string::npos) throw std::invalid_argument("model '" + spec + "' is not kind:size");
  kind = spec.substr(0, colon);
  const double dofs = static_cast<double>(bench::parse_size(spec.substr(colon + 1)));
  if (kind == "plate") return bench::clamped_plate(bench::divisions_for(static_cast<long>(dofs)));
  // 8-node grid of n x n elements: (3 n^2 + 2 n) nodes, 6 DOFs each, and
  // n^2 centres of 3 coordinates each.
  if (kind == "quad8") return bench::clamped_plate(static_cast<int>(std::lround(std::sqrt(dofs / 21.0))), true);
  // The same mesh with each centre condensed statically: what the centres cost.
  if (kind == "quad8c") return bench::clamped_plate(static_cast<int>(std::lround(std::sqrt(dofs / 21.0))), true, false);
  if (kind == "lattice") return beam_lattice(static_cast<int>(std::lround(std::cbrt(dofs / 6.0))));
  // 32 nodes per section ring, 6 DOFs each.
  if (kind == "girder") return shell_girder(static_cast<int>(std::lround(dofs / 192.0)));
  // per bay: 2 x 4 rail nodes + 3 interior rung nodes = 11 nodes, 66 DOFs.
  if (kind == "ladder") return beam_ladder(static_cast<int>(std::lround(dofs / 66.0)));
  throw std::invalid_argument("unknown model kind '" + kind + "' (plate, quad8, quad8c, girder, lattice, ladder)");
}

}  // namespace rigflex::bench
