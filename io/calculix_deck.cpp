#include "io/calculix_deck.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "fe/beam_element.hpp"
#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::io {
namespace {

// Text of a double for ccx, which reads at most 20 characters per field
// and tells reals from integers by the decimal point (a *SPRING line "20000"
// is read as a DOF number): the shortest round-trip form if it fits, else
// fewer significant digits, always with a '.'.
std::string num(double v) {
  std::array<char, 32> buf{};
  auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  std::string s(buf.data(), r.ptr);
  for (int digits = 16; s.size() > 19 && digits > 6; --digits) {
    std::snprintf(buf.data(), buf.size(), "%.*g", digits, v);
    s = buf.data();
  }
  if (s.find('.') == std::string::npos) {
    const auto e = s.find('e');
    s.insert(e == std::string::npos ? s.size() : e, ".");
  }
  return s;
}

std::string vec_text(const fe::Vec3& v) { return num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()); }

[[noreturn]] void unsupported(const std::string& what) { throw std::invalid_argument("CalculiX export: " + what); }

class InputWriter {
 public:
  InputWriter(const fe::Model& m, const CalculixOptions& opt) : m_(m), opt_(opt) {}

  std::string write() {
    m_.validate();
    opt_.validate();
    number_nodes();
    mark_element_nodes();
    check_unsupported();

    out_.reserve(m_.nodes.size() * 80 + m_.shells.size() * 60 + 4096);
    out_ += std::string("** ") + (opt_.dialect == CalculixDialect::abaqus ? "Abaqus" : "CalculiX 2.20") +
            " *FREQUENCY input written by rigflex (io/calculix_deck.cpp).\n";
    out_ += "** Beams are B32R, MITC4 shells S4, 8-node shells S8R; ccx expands them into\n";
    out_ += "** C3D20R / C3D8I solids internally. Solids are C3D8I, C3D20 and C3D10.\n";
    if (!opt_.heading.empty()) out_ += "*HEADING\n" + opt_.heading + "\n";
    write_nodes();
    write_beams();
    write_shells();
    write_solids();
    write_anchors();
    write_materials();
    write_point_masses();
    write_springs();
    write_couplings();
    write_boundaries();
    if (opt_.matrix_storage) {
      // ccx stores K and M where it would factorize them and stops there:
      // no eigenvalues, no results, so no *NODE FILE.
      out_ += "*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n" + std::to_string(opt_.modes) + "\n*END STEP\n";
    } else {
      out_ += "*STEP\n*FREQUENCY\n" + std::to_string(opt_.modes) + "\n";
      if (opt_.write_node_file) out_ += "*NODE FILE\nU\n";
      out_ += "*END STEP\n";
    }
    return std::move(out_);
  }

  // After write(): the ccx number of every model node, and the first number
  // after the writer's own nodes (ccx numbers the nodes it generates from
  // there on).
  const std::unordered_map<fe::NodeId, long>& ccx_ids() const { return ccx_id_; }
  long first_free_node() const { return next_node_; }

 private:
  // ---- numbering -------------------------------------------------------
  void number_nodes() {
    // rigflex ids are kept when they are valid ccx node numbers; generated
    // nodes (beam mid nodes, rotation nodes, spring anchors) follow the
    // largest id.
    bool keep = true;
    for (const fe::Node& n : m_.nodes) keep = keep && n.id >= 1 && n.id < 100000000;
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      ccx_id_[m_.nodes[i].id] = keep ? m_.nodes[i].id : static_cast<long>(i + 1);
    next_node_ = 1;
    for (const auto& [id, c] : ccx_id_) next_node_ = std::max(next_node_, c + 1);
  }
  long id(fe::NodeId n) const { return ccx_id_.at(n); }
  long new_node(const fe::Vec3& x) {
    extra_nodes_.push_back({next_node_, x});
    return next_node_++;
  }

  void mark_element_nodes() {
    for (size_t i = 0; i < m_.beams.size(); ++i)
      for (fe::NodeId n : m_.beams[i].nodes) {
        element_node_.insert(n);
        first_beam_.emplace(n, i);
      }
    for (size_t i = 0; i < m_.shells.size(); ++i)
      for (fe::NodeId n : m_.shells[i].nodes) {
        element_node_.insert(n);
        first_shell_.emplace(n, i);
      }
  }
  bool in_elements(fe::NodeId n) const { return element_node_.count(n) != 0; }

  void check_unsupported() {
    std::set<std::string> used;
    for (const auto& b : m_.beams) used.insert(b.section);
    for (const std::string& name : used) {
      const fe::BeamSection& sec = m_.beam_sections.at(name);
      if (sec.shape == fe::SectionShape::ISection)
        unsupported("beam section '" + name +
                    "' is an I-section; ccx 2.20 *BEAM SECTION supports RECT, CIRC, PIPE and BOX only");
      if (sec.shape == fe::SectionShape::General)
        unsupported("beam section '" + name +
                    "' is a general section (A, Iy, Iz, J); ccx 2.20 offers SECTION=GENERAL only for the "
                    "U1 user element, not for B32R");
    }
    for (const auto& p : m_.point_masses)
      for (double j : p.inertia)
        if (j != 0.0 && opt_.dialect == CalculixDialect::calculix)
          unsupported("point mass '" + p.id +
                      "' has rotary inertia; ccx 2.20 MASS elements carry translational mass only (Abaqus's "
                      "ROTARYI does: export for Abaqus)");
    for (const auto& s : m_.springs)
      for (int d = 3; d < 6; ++d)
        if (s.stiffness[static_cast<size_t>(d)] != 0.0)
          unsupported("spring '" + s.id + "' has a rotational stiffness; only translational springs are exported");
    if (!m_.distributing_couplings.empty())
      unsupported("distributing coupling '" + m_.distributing_couplings.front().id +
                  "': distributing couplings are not exported to ccx");
    for (const auto& c : m_.couplings)
      for (bool b : c.dofs)
        if (!b)
          unsupported("rigid coupling '" + c.id +
                      "' couples only some DOFs; only couplings of all six DOFs are exported");
  }

  // ---- nodes -----------------------------------------------------------
  void write_nodes() {
    // Mid nodes of the B32R elements first, so that every generated node
    // exists before the *NODE block is written.
    for (const auto& b : m_.beams)
      beam_mid_.push_back(new_node(0.5 * (m_.position(b.nodes[0]) + m_.position(b.nodes[1]))));
    for (const auto& c : m_.couplings) rot_node_.push_back(new_node(m_.position(c.reference)));
    make_knot_anchors();
    for (const auto& s : m_.springs)
      if (s.axial && *s.axial != 0.0 && !s.other)
        anchor_.push_back(new_node(m_.position(s.node) + s.direction->normalized()));
      else
        anchor_.push_back(0);

    out_ += "*NODE, NSET=NALL\n";
    // Shells' centre coordinates are rigflex's own (ccx's S8R has 8 nodes).
    std::set<fe::NodeId> centres;
    for (const fe::ShellElement& s : m_.shells)
      if (s.centre != 0) centres.insert(s.centre);
    for (const fe::Node& n : m_.nodes)
      if (!centres.count(n.id)) out_ += std::to_string(id(n.id)) + ", " + vec_text(n.x) + "\n";
    for (const auto& [k, x] : extra_nodes_) out_ += std::to_string(k) + ", " + vec_text(x) + "\n";
  }

  // ---- materials ------------------------------------------------------------
  // Model materials as given, and massless copies (zero density) for
  // elements with MassKind::None and for the knot anchors.
  enum class Variant { plain, massless };
  std::string material_name(const std::string& material, Variant v) {
    const auto key = std::make_pair(material, v == Variant::massless);
    auto it = material_names_.find(key);
    if (it != material_names_.end()) return it->second;
    const std::string name = "M" + std::to_string(material_names_.size() + 1);
    material_names_[key] = name;
    return name;
  }
  void write_materials() {
    for (const auto& [key, name] : material_names_) {
      const fe::Material& mat = m_.materials.at(key.first);
      out_ += "** material '" + key.first + "'" + (key.second ? " (massless copy)" : "") + "\n";
      out_ += "*MATERIAL, NAME=" + name + "\n*ELASTIC\n" + num(mat.E) + ", " + num(mat.nu) + "\n";
      out_ += "*DENSITY\n" + num(key.second ? 0.0 : mat.rho) + "\n";
    }
  }

  // ---- knot anchors -----------------------------------------------------
  // ccx gives a beam or shell node rotational DOFs only where it builds a
  // "knot" (a rigid body of all expanded nodes at the node, with a rotation
  // node); it does so where elements with different tangents or normals
  // meet, not where an *EQUATION or *RIGID BODY refers to the node's
  // rotations: such terms are silently without effect, and a coupling to a
  // node in the middle of a straight member leaves the rotation free (found
  // by running ccx 2.20: the coupled masses came out as zero-frequency
  // modes). So every beam or shell node whose rotations enter a coupling
  // equation gets a short anchor beam at right angles to its element, which
  // makes ccx build a knot there. The anchor is massless and free at its far
  // end: it follows the knot rigidly and stores no energy, so it changes
  // neither stiffness nor mass (a clamped anchor would act as a spring of
  // stiffness E A / L). It has the element's material (no extreme
  // stiffness ratios) and a square section a tenth of its length.
  struct Anchor {
    long mid = 0, far = 0;  // far end: free
    fe::NodeId node = 0;
    fe::Vec3 n1;
    double length = 0;
    std::string material;
  };

  void make_knot_anchors() {
    std::set<fe::NodeId> nodes;
    for (const auto& c : m_.couplings) {
      for (fe::NodeId d : c.dependents)
        if (in_elements(d)) nodes.insert(d);
      if (in_elements(c.reference)) nodes.insert(c.reference);
    }
    for (fe::NodeId n : nodes) {
      Anchor a;
      a.node = n;
      fe::Vec3 dir;
      if (auto b = first_beam_.find(n); b != first_beam_.end()) {
        const fe::BeamElement& e = m_.beams[b->second];
        const Eigen::Matrix3d R = fe::beam_local_axes(m_.position(e.nodes[0]), m_.position(e.nodes[1]), e.orientation);
        dir = R.row(1).transpose();
        a.n1 = R.row(0).transpose();
        const fe::BeamSection& sec = m_.beam_sections.at(e.section);
        a.length = std::max({sec.width, sec.height, sec.diameter, std::sqrt(std::max(sec.A, 0.0))});
        a.material = sec.material;
      } else {
        const fe::ShellElement& e = m_.shells[first_shell_.at(n)];
        const fe::Vec3 x0 = m_.position(e.nodes[0]), x1 = m_.position(e.nodes[1]), x2 = m_.position(e.nodes[2]),
                       x3 = m_.position(e.nodes[3]);
        dir = (x2 - x0).cross(x3 - x1).normalized();
        const fe::Vec3 edge = x1 - x0;
        a.n1 = (edge - edge.dot(dir) * dir).normalized();
        const fe::ShellSection& sec = m_.shell_sections.at(e.section);
        a.length = 2.0 * sec.thickness;
        a.material = sec.material;
      }
      const fe::Vec3 x = m_.position(n);
      a.mid = new_node(x + 0.5 * a.length * dir);
      a.far = new_node(x + a.length * dir);
      anchors_.push_back(a);
    }
  }

  void write_anchors() {
    int k = 0;
    for (const Anchor& a : anchors_) {
      const std::string elset = "EA" + std::to_string(++k);
      out_ += "** knot anchor of node " + std::to_string(id(a.node)) + "\n*ELEMENT, TYPE=B32R, ELSET=" + elset + "\n" +
              std::to_string(++element_) + ", " + std::to_string(id(a.node)) + ", " + std::to_string(a.mid) + ", " +
              std::to_string(a.far) + "\n";
      out_ += "*BEAM SECTION, ELSET=" + elset + ", MATERIAL=" + material_name(a.material, Variant::massless) +
              ", SECTION=RECT\n" + num(0.1 * a.length) + ", " + num(0.1 * a.length) + "\n" + vec_text(a.n1) + "\n";
    }
  }

  // ---- beams -------------------------------------------------------------
  void write_beams() {
    // One element set per (section, mass kind, 1-direction).
    struct Group {
      std::string section;
      bool massless = false;
      fe::Vec3 n1;
      std::vector<size_t> beams;
    };
    std::map<std::string, Group> groups;
    for (size_t i = 0; i < m_.beams.size(); ++i) {
      const fe::BeamElement& b = m_.beams[i];
      const Eigen::Matrix3d R = fe::beam_local_axes(m_.position(b.nodes[0]), m_.position(b.nodes[1]), b.orientation);
      const fe::Vec3 n1 = R.row(1).transpose();  // ccx n1 = rigflex local y, so n2 = t x n1 = local z
      const bool massless = b.mass == fe::MassKind::None;
      const std::string key = b.section + "|" + (massless ? "0" : "1") + "|" + vec_text(n1);
      Group& g = groups[key];
      g.section = b.section;
      g.massless = massless;
      g.n1 = n1;
      g.beams.push_back(i);
    }
    int k = 0;
    for (const auto& [key, g] : groups) {
      const std::string elset = "EB" + std::to_string(++k);
      out_ += "** beam section '" + g.section + "'\n*ELEMENT, TYPE=B32R, ELSET=" + elset + "\n";
      for (size_t i : g.beams) {
        const fe::BeamElement& b = m_.beams[i];
        out_ += std::to_string(++element_) + ", " + std::to_string(id(b.nodes[0])) + ", " +
                std::to_string(beam_mid_[i]) + ", " + std::to_string(id(b.nodes[1])) + "\n";
      }
      const fe::BeamSection& s = m_.beam_sections.at(g.section);
      const std::string mat = material_name(s.material, g.massless ? Variant::massless : Variant::plain);
      std::string kind, dims;
      switch (s.shape) {
        case fe::SectionShape::Rectangle:
          kind = "RECT";
          dims = num(s.width) + ", " + num(s.height);
          break;
        case fe::SectionShape::Circle:
          kind = "CIRC";
          dims = opt_.dialect == CalculixDialect::abaqus ? num(0.5 * s.diameter)
                                                         : num(s.diameter) + ", " + num(s.diameter);
          break;
        case fe::SectionShape::Tube:
          kind = "PIPE";
          dims = num(0.5 * s.diameter) + ", " + num(s.wall);
          break;
        case fe::SectionShape::Box: {
          kind = "BOX";
          const double tw = s.web_thickness > 0 ? s.web_thickness : s.wall;        // walls at +-y (n1)
          const double tf = s.flange_thickness > 0 ? s.flange_thickness : s.wall;  // walls at +-z (n2)
          dims =
              num(s.width) + ", " + num(s.height) + ", " + num(tw) + ", " + num(tf) + ", " + num(tw) + ", " + num(tf);
          break;
        }
        default:
          unsupported("beam section '" + g.section + "' has no ccx equivalent");
      }
      out_ += "*BEAM SECTION, ELSET=" + elset + ", MATERIAL=" + mat + ", SECTION=" + kind + "\n" + dims + "\n" +
              vec_text(g.n1) + "\n";
    }
  }

  // ---- shells ------------------------------------------------------------
  void write_shells() {
    struct Group {
      std::string section;
      bool massless = false;
      const fe::ShellType* type = nullptr;
      std::vector<size_t> shells;
    };
    // Keyed by the type's place in fe::shell_types(), so that the deck's
    // order does not depend on addresses.
    std::map<std::tuple<std::string, bool, size_t>, Group> groups;
    for (size_t i = 0; i < m_.shells.size(); ++i) {
      const fe::ShellElement& s = m_.shells[i];
      const bool massless = s.mass == fe::MassKind::None;
      const fe::ShellType& type = fe::shell_type(s);
      Group& g = groups[{s.section, massless, static_cast<size_t>(&type - fe::shell_types().data())}];
      g.section = s.section;
      g.massless = massless;
      g.type = &type;
      g.shells.push_back(i);
    }
    int k = 0;
    for (const auto& [key, g] : groups) {
      const std::string elset = "ES" + std::to_string(++k);
      out_ += "** shell section '" + g.section + "'\n*ELEMENT, TYPE=" + std::string(g.type->calculix) +
              ", ELSET=" + elset + "\n";
      for (size_t i : g.shells) {
        out_ += std::to_string(++element_);
        // rigflex's node order (corners counter-clockwise, then mid-sides
        // 1-2, 2-3, 3-4, 4-1) is ccx's S4 / S8 order.
        for (fe::NodeId n : m_.shells[i].nodes) out_ += ", " + std::to_string(id(n));
        out_ += "\n";
      }
      const fe::ShellSection& s = m_.shell_sections.at(g.section);
      out_ += "*SHELL SECTION, ELSET=" + elset +
              ", MATERIAL=" + material_name(s.material, g.massless ? Variant::massless : Variant::plain) + "\n" +
              num(s.thickness) + "\n";
    }
  }

  // ---- solids ------------------------------------------------------------
  void write_solids() {
    // One element set per (material, massless or not, type), keyed by the
    // type's place in fe::solid_types() so that the deck's order is fixed.
    // Lumped solids are written with ccx's consistent mass, as shells are.
    std::map<std::tuple<std::string, bool, size_t>, std::vector<size_t>> groups;
    for (size_t i = 0; i < m_.solids.size(); ++i) {
      const fe::SolidElement& s = m_.solids[i];
      const size_t type = static_cast<size_t>(&fe::solid_type(s) - fe::solid_types().data());
      groups[{s.material, s.mass == fe::MassKind::None, type}].push_back(i);
    }
    int k = 0;
    for (const auto& [key, members] : groups) {
      const auto& [material, massless, type] = key;
      const std::string elset = "EV" + std::to_string(++k);
      out_ += "** solids of material '" + material +
              "'\n*ELEMENT, TYPE=" + std::string(fe::solid_types()[type].calculix) + ", ELSET=" + elset + "\n";
      for (size_t i : members) {
        // rigflex's node orders are ccx's (fe/solid_element.hpp); ccx wants
        // at most 16 entries on a line, so the hex20's last four continue.
        std::string line = std::to_string(++element_);
        int entries = 1;
        for (fe::NodeId n : m_.solids[i].nodes) {
          if (entries == 16) {
            out_ += line + ",\n";
            line.clear();
            entries = 0;
          }
          line += (line.empty() ? "" : ", ") + std::to_string(id(n));
          ++entries;
        }
        out_ += line + "\n";
      }
      out_ += "*SOLID SECTION, ELSET=" + elset +
              ", MATERIAL=" + material_name(material, massless ? Variant::massless : Variant::plain) + "\n";
    }
  }

  // ---- point masses ---------------------------------------------------------
  void write_point_masses() {
    int k = 0;
    for (const auto& p : m_.point_masses) {
      if (p.mass == 0.0) continue;
      const std::string elset = "EM" + std::to_string(++k);
      out_ += "** point mass '" + p.id + "'\n*ELEMENT, TYPE=MASS, ELSET=" + elset + "\n" + std::to_string(++element_) +
              ", " + std::to_string(id(p.node)) + "\n";
      out_ += "*MASS, ELSET=" + elset + "\n" + num(p.mass) + "\n";
    }
    // Abaqus only (check_unsupported): the tensor's terms about the node, as rigflex's.
    for (const auto& p : m_.point_masses) {
      if (std::all_of(p.inertia.begin(), p.inertia.end(), [](double j) { return j == 0.0; })) continue;
      const std::string elset = "EJ" + std::to_string(++k);
      out_ += "** rotary inertia of point mass '" + p.id + "'\n*ELEMENT, TYPE=ROTARYI, ELSET=" + elset + "\n" +
              std::to_string(++element_) + ", " + std::to_string(id(p.node)) + "\n*ROTARY INERTIA, ELSET=" + elset +
              "\n";
      for (size_t j = 0; j < 6; ++j) out_ += (j ? ", " : "") + num(p.inertia[j]);
      out_ += "\n";
    }
  }

  // ---- springs ---------------------------------------------------------------
  void write_springs() {
    int k = 0;
    for (size_t i = 0; i < m_.springs.size(); ++i) {
      const fe::Spring& s = m_.springs[i];
      for (int d = 0; d < 3; ++d) {
        const double kd = s.stiffness[static_cast<size_t>(d)];
        if (kd == 0.0) continue;
        const std::string elset = "EK" + std::to_string(++k);
        if (s.other) {
          out_ += "** spring '" + s.id + "'\n*ELEMENT, TYPE=SPRING2, ELSET=" + elset + "\n" +
                  std::to_string(++element_) + ", " + std::to_string(id(s.node)) + ", " + std::to_string(id(*s.other)) +
                  "\n";
          out_ += "*SPRING, ELSET=" + elset + "\n" + std::to_string(d + 1) + ", " + std::to_string(d + 1) + "\n" +
                  num(kd) + "\n";
        } else {
          out_ += "** spring '" + s.id + "'\n*ELEMENT, TYPE=SPRING1, ELSET=" + elset + "\n" +
                  std::to_string(++element_) + ", " + std::to_string(id(s.node)) + "\n";
          out_ += "*SPRING, ELSET=" + elset + "\n" + std::to_string(d + 1) + "\n" + num(kd) + "\n";
        }
      }
      if (!s.axial || *s.axial == 0.0) continue;
      long a = id(s.node), b = 0;
      if (s.other) {
        b = id(*s.other);
        const fe::Vec3 line = m_.position(*s.other) - m_.position(s.node);
        if (s.direction && line.norm() > 0 && line.normalized().cross(s.direction->normalized()).norm() > 1e-9)
          unsupported("spring '" + s.id +
                      "': an axial spring between two nodes along a direction other than the line between "
                      "them has no ccx element (SPRINGA acts along the line)");
        if (line.norm() == 0.0)
          unsupported("spring '" + s.id + "': an axial spring between coincident nodes has no ccx element");
      } else {
        b = anchor_[i];  // clamped below
        anchored_.push_back(b);
      }
      const std::string elset = "EK" + std::to_string(++k);
      out_ += "** axial spring '" + s.id + "'\n*ELEMENT, TYPE=SPRINGA, ELSET=" + elset + "\n" +
              std::to_string(++element_) + ", " + std::to_string(a) + ", " + std::to_string(b) + "\n";
      // Abaqus's SPRINGA has an empty first data line.
      out_ += "*SPRING, ELSET=" + elset + "\n" + (opt_.dialect == CalculixDialect::abaqus ? ",\n" : "") +
              num(*s.axial) + "\n";
    }
  }

  // ---- rigid couplings -------------------------------------------------------
  // Linear multipoint constraints of a rigid link (RBE2), written as
  // *EQUATION rather than *RIGID BODY: ccx's *RIGID BODY ties only the
  // translations of beam and shell nodes and leaves the rotation about the
  // line undefined when the nodes are collinear (one dependent), whereas
  // rigflex's coupling also drives the dependents' rotations. For a
  // reference r with rotation theta (the translations of a generated
  // rotation node q, as in ccx's ROT NODE convention) and a dependent d:
  //   u_d - u_r - theta x (x_d - x_r) = 0   (3 equations, u_d dependent)
  //   theta_d - theta = 0                    (if d belongs to beams/shells)
  //   theta_r - theta = 0                    (if r belongs to beams/shells)
  // The rotational terms of beam and shell nodes act through the knots that
  // the anchors (make_knot_anchors) create there.
  void write_couplings() {
    for (size_t i = 0; i < m_.couplings.size(); ++i) {
      const fe::RigidCoupling& c = m_.couplings[i];
      const long q = rot_node_[i], r = id(c.reference);
      const fe::Vec3 xr = m_.position(c.reference);
      out_ += "** rigid coupling '" + c.id + "': reference " + std::to_string(r) + ", rotation node " +
              std::to_string(q) + "\n*EQUATION\n";
      auto term = [](long node, int dof, double coef) {
        return std::to_string(node) + ", " + std::to_string(dof) + ", " + num(coef);
      };
      for (fe::NodeId dn : c.dependents) {
        const long d = id(dn);
        fe::Vec3 a = m_.position(dn) - xr;
        // Rounding residue of the mesh coordinates is not a lever arm (and
        // ccx rejects equations with terms of ~1e-16).
        for (int k = 0; k < 3; ++k)
          if (std::abs(a[k]) < 1e-12 * a.norm()) a[k] = 0.0;
        // (theta x a)_0 = theta_1 a_2 - theta_2 a_1, and cyclically.
        for (int k = 0; k < 3; ++k) {
          const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          std::vector<std::string> terms{term(d, k + 1, 1.0), term(r, k + 1, -1.0)};
          if (a[k2] != 0.0) terms.push_back(term(q, k1 + 1, -a[k2]));
          if (a[k1] != 0.0) terms.push_back(term(q, k2 + 1, a[k1]));
          out_ += std::to_string(terms.size()) + "\n";
          for (size_t t = 0; t < terms.size(); ++t) out_ += terms[t] + (t + 1 == terms.size() ? "\n" : ", ");
        }
        if (in_elements(dn))
          for (int k = 1; k <= 3; ++k) out_ += "2\n" + term(d, k + 3, 1.0) + ", " + term(q, k, -1.0) + "\n";
      }
      if (in_elements(c.reference))
        for (int k = 1; k <= 3; ++k) out_ += "2\n" + term(r, k + 3, 1.0) + ", " + term(q, k, -1.0) + "\n";
      rot_of_reference_[c.reference] = q;
    }
  }

  // ---- supports ----------------------------------------------------------------
  void write_boundaries() {
    std::string b;
    for (const fe::Support& s : m_.supports) {
      const long n = id(s.node);
      const auto rot = rot_of_reference_.find(s.node);
      for (int d = 0; d < 6; ++d) {
        if (!s.fixed[static_cast<size_t>(d)]) continue;
        if (d < 3) {
          b += std::to_string(n) + ", " + std::to_string(d + 1) + ", " + std::to_string(d + 1) + "\n";
        } else if (rot != rot_of_reference_.end()) {
          // rotation of a coupling reference: it lives in the rotation
          // node's translations (the reference's own rotations, if any,
          // are dependent DOFs of the coupling equations)
          b += std::to_string(rot->second) + ", " + std::to_string(d - 2) + ", " + std::to_string(d - 2) + "\n";
        } else if (in_elements(s.node)) {
          b += std::to_string(n) + ", " + std::to_string(d + 1) + ", " + std::to_string(d + 1) + "\n";
        }
        // else: a rotation nothing stiffens (rigflex drops it as unused)
      }
    }
    for (long a : anchored_) b += std::to_string(a) + ", 1, 3\n";
    if (!b.empty()) out_ += "*BOUNDARY\n" + b;
  }

  const fe::Model& m_;
  const CalculixOptions& opt_;
  std::string out_;
  std::unordered_map<fe::NodeId, long> ccx_id_;
  std::unordered_set<fe::NodeId> element_node_;
  std::unordered_map<fe::NodeId, size_t> first_beam_, first_shell_;
  std::vector<Anchor> anchors_;
  long next_node_ = 1;
  long element_ = 0;
  std::vector<std::pair<long, fe::Vec3>> extra_nodes_;
  std::vector<long> beam_mid_, rot_node_, anchor_, anchored_;
  std::map<fe::NodeId, long> rot_of_reference_;
  std::map<std::pair<std::string, bool>, std::string> material_names_;
};

}  // namespace

void CalculixOptions::validate() const {
  if (modes < 1) throw std::invalid_argument("CalculixOptions::modes must be at least 1");
  if (heading.find('\n') != std::string::npos)
    throw std::invalid_argument("CalculixOptions::heading must be a single line");
}

CalculixDeck calculix_deck(const fe::Model& model, const CalculixOptions& opt) {
  InputWriter writer(model, opt);
  CalculixDeck deck;
  deck.text = writer.write();
  deck.ccx_ids = writer.ccx_ids();
  deck.first_free_node = writer.first_free_node();
  return deck;
}

std::string calculix_input(const fe::Model& model, const CalculixOptions& opt) {
  return calculix_deck(model, opt).text;
}

}  // namespace rigflex::io
