#include "fe/element_loop.hpp"

#include <map>
#include <string>

#include "fe/beam_element.hpp"
#include "fe/discrete_elements.hpp"
#include "fe/error.hpp"
#include "fe/shell_point_mass.hpp"
#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::fe {
namespace {

// Inputs in their physical ranges can still make an element whose matrices
// overflow or divide by zero (a shell whose corners lie nearly on a line);
// such a matrix would spread NaN through the whole solve, so it is refused
// here, named, before it is assembled.
void require_finite(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const char* kind, const std::string& id) {
  const bool k_ok = K.allFinite(), m_ok = M.allFinite();
  if (k_ok && m_ok) return;
  throw ModelError({kind, id, ""}, std::string(kind) + " '" + id + "': its " +
                                       (k_ok   ? "mass matrix is"
                                        : m_ok ? "stiffness matrix is"
                                               : "stiffness and mass matrices are") +
                                       " not finite (degenerate geometry, or values at the edge of their range "
                                       "multiplied past a double)");
}

std::vector<long> node_dofs(const Model& model, const std::vector<NodeId>& ids) {
  std::vector<long> dofs;
  dofs.reserve(6 * ids.size());
  for (NodeId id : ids) {
    const long base = 6 * static_cast<long>(model.node_index(id));
    for (int d = 0; d < 6; ++d) dofs.push_back(base + d);
  }
  return dofs;
}

void visit_beams(const Model& model, const ElementVisitor& visit) {
  std::map<std::string, BeamProperties> cache;
  for (const BeamElement& b : model.beams) {
    auto it = cache.find(b.section);
    if (it == cache.end()) {
      const BeamSection& s = model.beam_sections.at(b.section);
      const Material& m = model.materials.at(s.material);
      BeamProperties p;
      p.E = m.E;
      p.G = m.G();
      p.rho = m.rho;
      p.section = section_properties(s, m.nu);
      it = cache.emplace(b.section, p).first;
    }
    BeamProperties p = it->second;
    p.theory = b.theory;
    p.mass = b.mass;
    p.rotary_inertia = b.rotary_inertia;
    const ElementMatrices e = beam_matrices(model.position(b.nodes[0]), model.position(b.nodes[1]), b.orientation, p);
    require_finite(e.K, e.M, "beam", b.id);
    visit(node_dofs(model, {b.nodes[0], b.nodes[1]}), e.K, e.M);
  }
}

void visit_shells(const Model& model, const ElementVisitor& visit) {
  std::vector<Vec3> x;
  for (const ShellElement& s : model.shells) {
    const ShellSection& sec = model.shell_sections.at(s.section);
    const Material& m = model.materials.at(sec.material);
    const ShellProperties p{m.E, m.nu, m.rho, sec.thickness, s.mass};
    x.clear();
    for (NodeId id : s.nodes) x.push_back(model.position(id));
    const ShellType& type = shell_type(s);
    const ElementMatrices e = s.centre != 0 ? type.matrices_with_own(x, p) : type.matrices(x, p);
    require_finite(e.K, e.M, "shell", s.id);
    std::vector<long> dofs = node_dofs(model, s.nodes);
    if (s.centre != 0) {
      const long base = 6 * static_cast<long>(model.node_index(s.centre));
      for (int d = 0; d < type.own_coordinates; ++d) dofs.push_back(base + d);
    }
    visit(dofs, e.K, e.M);
  }
}

// Solids' nodes carry translations only: their matrices act on the first
// three of each node's six DOFs.
void visit_solids(const Model& model, const ElementVisitor& visit) {
  std::vector<Vec3> x;
  std::vector<long> dofs;
  for (const SolidElement& s : model.solids) {
    const Material& m = model.materials.at(s.material);
    x.clear();
    dofs.clear();
    for (NodeId id : s.nodes) {
      x.push_back(model.position(id));
      const long base = 6 * static_cast<long>(model.node_index(id));
      for (int d = 0; d < 3; ++d) dofs.push_back(base + d);
    }
    const ElementMatrices e = solid_type(s).matrices(x, {m.E, m.nu, m.rho, s.mass});
    require_finite(e.K, e.M, "solid", s.id);
    visit(dofs, e.K, e.M);
  }
}

void visit_discrete(const Model& model, const ElementVisitor& visit) {
  const Eigen::MatrixXd zero6 = Eigen::MatrixXd::Zero(6, 6);
  const std::vector<PointMassMatrix> masses = point_mass_matrices(model);
  for (size_t i = 0; i < masses.size(); ++i) {
    const Eigen::MatrixXd& m = masses[i].M;
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(m.rows(), m.cols());
    require_finite(zero, m, "point_mass", model.point_masses[i].id);
    visit(masses[i].dofs, zero, m);
  }
  for (const Spring& s : model.springs) {
    const Vec3& xa = model.position(s.node);
    const Vec3 xb = s.other ? model.position(*s.other) : xa;
    const Eigen::Matrix<double, 6, 6> k = spring_stiffness(s, xa, xb);
    require_finite(k, zero6, "spring", s.id);
    if (!s.other) {
      visit(node_dofs(model, {s.node}), k, zero6);
      continue;
    }
    Eigen::MatrixXd k12(12, 12);
    k12 << k, -k, -k, k;
    visit(node_dofs(model, {s.node, *s.other}), k12, Eigen::MatrixXd::Zero(12, 12));
  }
}

// A superelement's dense matrices on its interface DOFs and its modal
// nodes' first DOF (Model::validate checked their sizes and symmetry).
void visit_superelements(const Model& model, const ElementVisitor& visit) {
  std::vector<long> dofs;
  for (const Superelement& e : model.superelements) {
    dofs.clear();
    for (const SuperelementDof& d : e.interface)
      dofs.push_back(6 * static_cast<long>(model.node_index(d.node)) + d.local);
    for (NodeId id : e.modal_nodes) dofs.push_back(6 * static_cast<long>(model.node_index(id)));
    require_finite(e.K, e.M, "superelement", e.id);
    visit(dofs, e.K, e.M);
  }
}

}  // namespace

void check_element_matrices(const Model& model) {
  for_each_element(model, [](const std::vector<long>&, const Eigen::MatrixXd&, const Eigen::MatrixXd&) {});
}

long element_count(const Model& model) {
  return static_cast<long>(model.beams.size() + model.shells.size() + model.solids.size() + model.point_masses.size() +
                           model.springs.size() + model.superelements.size());
}

void for_each_element(const Model& model, const ElementVisitor& visit) {
  visit_beams(model, visit);
  visit_shells(model, visit);
  visit_solids(model, visit);
  visit_discrete(model, visit);
  visit_superelements(model, visit);
}

}  // namespace rigflex::fe
