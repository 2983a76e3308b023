#pragma once
// Small frame models shared by the test suites.
#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "fe/meshers.hpp"
#include "fe/model.hpp"
#include "fe/node_merger.hpp"

namespace rigflex::test {

// Supports the listed local DOFs (fe::Dof values) of one node / every node.
void fix(fe::Model& m, fe::NodeId node, std::initializer_list<int> dofs);
void fix_all_nodes(fe::Model& m, std::initializer_list<int> dofs);
// Holds all six DOFs of `node` (support `id`).
void clamp(fe::Model& m, const std::string& id, fe::NodeId node);

// An empty model with the one material the steel models use, "steel"
// (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3).
fe::Model steel_model();

// Beam sections of material "steel".
fe::BeamSection tube_section(const std::string& name, double diameter, double wall);
fe::BeamSection rect_section(const std::string& name, double width, double height);
fe::BeamSection box_section(const std::string& name, double width, double height, double wall);
// A box whose webs (walls at +-y) and flanges (walls at +-z) differ.
fe::BeamSection box_section(const std::string& name, double width, double height, double web_thickness,
                            double flange_thickness);

// fe::mesh_member with the MemberSpec defaults for everything but these:
// node ids from `from` to `to`.
std::vector<fe::NodeId> member(fe::Model& m, fe::NodeMerger& merger, const std::string& id, const fe::Vec3& from,
                               const fe::Vec3& to, int elements, const std::string& section);

// An axial spring between two nodes (along their line unless `direction`
// is given), or from `a` to ground along `direction`.
fe::Spring axial_spring(const std::string& id, fe::NodeId a, std::optional<fe::NodeId> b, double k,
                        std::optional<fe::Vec3> direction = std::nullopt);
// Six uncoupled stiffnesses in global axes, from `node` to ground.
fe::Spring grounded_spring(const std::string& id, fe::NodeId node, const std::array<double, 6>& stiffness);

// The portal frame of shared/verification/portal_frame_sway_closed_form.yaml
// in the x-y plane: massless, axially rigid Euler-Bernoulli members (4
// elements each), columns clamped, 5000 kg translational point masses at the
// top corners (nodes returned in `corners`). Out-of-plane DOFs held.
fe::Model portal_frame(double beam_I, std::array<fe::NodeId, 2>* corners = nullptr);

// A steel fixed frame of a three-rod rig (box columns 3.2 m high, box cross
// beams, three upper joints coupled below the beams): grounded, node set
// "upper_joints". elements_per_member sets the mesh.
fe::Model rig_fixed_frame(int elements_per_member = 4);

// A steel carrying frame (2 x 1 bays of box beams, 3.0 x 2.0 m) with three
// lower joints and a 400 kg point mass with inertia at mid-span: floating,
// node set "lower_joints".
fe::Model rig_carrying_frame(int elements_per_member = 4);  // even: a node at the centre

// A length x width plate in the xy plane from the origin, section "plate"
// (steel, `thickness`), nx x ny shells (8-node if `quadratic`), clamped
// (all six DOFs) along x = 0. Returns the node grid.
fe::PatchNodes clamped_plate(fe::Model& m, double length, double width, double thickness, int nx, int ny,
                             bool quadratic);

}  // namespace rigflex::test
