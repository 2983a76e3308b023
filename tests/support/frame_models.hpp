#pragma once
// Small frame models shared by the test suites.
#include <array>
#include <initializer_list>

#include "fe/model.hpp"

namespace rigflex::test {

// Supports the listed local DOFs (fe::Dof values) of one node / every node.
void fix(fe::Model& m, fe::NodeId node, std::initializer_list<int> dofs);
void fix_all_nodes(fe::Model& m, std::initializer_list<int> dofs);

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

}  // namespace rigflex::test
