#include "io/model_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "fe/dof.hpp"
#include "fe/element_loop.hpp"
#include "fe/error.hpp"
#include "fe/meshers.hpp"
#include "fe/node_selection.hpp"
#include "fe/shell_centres.hpp"
#include "fe/shell_types.hpp"
#include "fe/solid_types.hpp"
#include "io/gmsh_mesh.hpp"
#include "io/input_error.hpp"
#include "io/reduced_export.hpp"
#include "io/yaml_document.hpp"
#include "io/yaml_fields.hpp"

namespace rigflex::io {
namespace {

using fe::NodeId;
using fe::Vec3;

constexpr double kNodeTolerance = 1e-6;  // [m] for `at:` references and mesher merging
// Elements along one edge of a mesher. 10000 x 10000 shells would be 6e8
// DOFs; the largest models solved here are 1e6 (docs/eigen-solver.md).
constexpr long kMaxDivisions = 10000;
// Elements one mesher may make: 4e6 shells are about 2.4e7 DOFs, 24 x the
// largest model solved here.
constexpr double kMaxGenerated = 4e6;

// Where each entity was defined, so that semantic errors found by
// fe::Model::validate can point at a line; an id given to two entities of
// one kind is refused here, with both lines (otherwise one of them would be
// reported for errors in the other, and references by id are ambiguous).
class SourceMap {
 public:
  explicit SourceMap(std::string file) : file_(std::move(file)) {}
  void add(const std::string& kind, const std::string& id, const YAML::Node& n) {
    const auto [it, fresh] = lines_.emplace(kind + "\n" + id, n);
    if (fresh) return;
    const int first = YamlContext::line_of(it->second), here = YamlContext::line_of(n);
    const std::string what = kind == "node" ? "node id" : kind + " id";
    throw InputError(file_, here, n.IsMap() && n["id"].IsDefined() ? "id" : "",
                     what + " '" + id + "' is given twice (" +
                         (first == here ? std::string("by this entry") : "first at line " + std::to_string(first)) +
                         "): ids must be unique");
  }
  YAML::Node find(const fe::EntityRef& e) const {
    auto it = lines_.find(e.kind + "\n" + e.id);
    if (it == lines_.end()) return YAML::Node();
    if (!e.key.empty() && it->second.IsMap() && it->second[e.key].IsDefined()) return it->second[e.key];
    return it->second;
  }

 private:
  std::string file_;
  std::map<std::string, YAML::Node> lines_;
};

class ModelFileReader {
 public:
  ModelFileReader(const YamlContext& ctx, fe::Model& model, SourceMap& src) : c_(ctx), m_(model), src_(src) {}

  void read(const YAML::Node& root) {
    c_.expect_map(root, "model file",
                  {"name",         "description", "materials",   "beam_sections",  "shell_sections", "nodes",
                   "node_sets",    "beams",       "shells",      "solids",         "members",        "shell_patches",
                   "solid_blocks", "box_girders", "fixed_frame", "carrying_frame", "point_masses",   "springs",
                   "supports",     "couplings",   "meshes",      "superelements",  "element_sets",   "assign"});
    each_entry(root, "materials", [&](const std::string& n, const YAML::Node& v) { material(n, v); });
    each_entry(root, "beam_sections", [&](const std::string& n, const YAML::Node& v) { beam_section(n, v); });
    each_entry(root, "shell_sections", [&](const std::string& n, const YAML::Node& v) { shell_section(n, v); });
    each_item(root, "nodes", [&](const YAML::Node& v) { node(v); });
    each_item(root, "beams", [&](const YAML::Node& v) { beam(v); });
    each_item(root, "shells", [&](const YAML::Node& v) { shell(v); });
    each_item(root, "solids", [&](const YAML::Node& v) { solid(v); });
    each_item(root, "members", [&](const YAML::Node& v) { member(v); });
    each_item(root, "shell_patches", [&](const YAML::Node& v) { patch(v); });
    each_item(root, "solid_blocks", [&](const YAML::Node& v) { solid_block(v); });
    each_item(root, "box_girders", [&](const YAML::Node& v) { box_girder(v); });
    each_item(root, "meshes", [&](const YAML::Node& v) { mesh(v); });
    each_item(root, "superelements", [&](const YAML::Node& v) { superelement(v); });
    if (root["fixed_frame"].IsDefined()) fixed_frame(root["fixed_frame"]);
    if (root["carrying_frame"].IsDefined()) carrying_frame(root["carrying_frame"]);
    each_entry(root, "node_sets", [&](const std::string& n, const YAML::Node& v) { node_set(n, v); });
    each_entry(root, "element_sets", [&](const std::string& n, const YAML::Node& v) { element_set(n, v); });
    each_item(root, "assign", [&](const YAML::Node& v) { assignment(v); });
    each_item(root, "point_masses", [&](const YAML::Node& v) { point_mass(v); });
    each_item(root, "springs", [&](const YAML::Node& v) { spring(v); });
    each_item(root, "supports", [&](const YAML::Node& v) { support(v); });
    each_item(root, "couplings", [&](const YAML::Node& v) { coupling(v); });
    add_modal_nodes();
    fe::add_shell_centres(m_);
  }

 private:
  template <class F>
  void each_item(const YAML::Node& root, const std::string& key, F f) {
    const YAML::Node list = root[key];
    if (!list.IsDefined()) return;
    c_.expect_sequence(list, key);
    for (size_t i = 0; i < list.size(); ++i) {
      index_ = key + "[" + std::to_string(i + 1) + "]";
      f(list[i]);
    }
  }
  template <class F>
  void each_entry(const YAML::Node& root, const std::string& key, F f) {
    const YAML::Node map = root[key];
    if (!map.IsDefined()) return;
    if (!map.IsMap()) c_.fail(map, key, "expected a mapping of names to definitions");
    for (const auto& kv : map) f(kv.first.as<std::string>(), kv.second);
  }
  std::string id_or_index(const YAML::Node& n) { return c_.text_or(n, "id", index_); }

  struct ElementRef {
    char kind = 'b';  // beam, shell, solid ('v')
    size_t index = 0;
  };
  std::map<std::string, std::vector<ElementRef>> element_sets_;

  struct Pending {
    fe::Superelement element;
    int modes = 0;
    fe::Vec3 centre;
  };
  std::vector<Pending> pending_;

  fe::MassKind mass_kind(const YAML::Node& n) {
    const std::string s = c_.text_or(n, "mass", "consistent");
    if (s == "consistent") return fe::MassKind::Consistent;
    if (s == "lumped") return fe::MassKind::Lumped;
    if (s == "none") return fe::MassKind::None;
    c_.fail(n["mass"], "mass", "expected consistent, lumped or none");
  }
  fe::BeamTheory theory(const YAML::Node& n) {
    const std::string s = c_.text_or(n, "theory", "timoshenko");
    if (s == "timoshenko") return fe::BeamTheory::Timoshenko;
    if (s == "euler-bernoulli") return fe::BeamTheory::EulerBernoulli;
    c_.fail(n["theory"], "theory", "expected timoshenko or euler-bernoulli");
  }
  // A mesher's element order, one of the shell types' (fe/shell_types.hpp);
  // the meshers generate 4- and 8-node quadrilaterals. Quadratic by default:
  // at a benchmark's own mesh (NAFEMS FV15, 12 x 12 on a 45-degree rhombus)
  // the 8-node shell is within 1.2 % of the targets and 0.3 % of the
  // plate's exact solution, MITC4 up to 16 % off (docs/fe-core.md).
  bool quadratic(const YAML::Node& n) {
    const std::string s = c_.text_or(n, "order", "quadratic");
    std::string known;
    for (const fe::ShellType& t : fe::shell_types()) {
      if (s == t.order) return t.nodes == 8;
      known += std::string(known.empty() ? "" : " or ") + t.order + " (" + t.name + ")";
    }
    c_.fail(n["order"], "order", "expected " + known);
  }
  // dofs_per_element: the DOFs a large mesh has per element (its nodes per
  // element, shared, times the DOFs per node).
  void bounded_mesh(const YAML::Node& at, double elements, double dofs_per_element) {
    if (elements > kMaxGenerated) {
      char msg[200];
      std::snprintf(msg, sizeof msg,
                    "these divisions make %.3g elements (about %.2g DOFs); at most %.0e per mesher: a model this "
                    "size does not fit a machine's memory",
                    elements, dofs_per_element * elements, kMaxGenerated);
      c_.fail(at, "divisions", msg);
    }
  }
  std::pair<int, int> pair_of_ints(const YAML::Node& n, const std::string& key) {
    const YAML::Node v = c_.required(n, key);
    if (!v.IsSequence() || v.size() != 2) c_.fail(v, key, "expected two integers [n1, n2]");
    return {c_.as_count(v[0], key, kMaxDivisions), c_.as_count(v[1], key, kMaxDivisions)};
  }
  std::vector<Vec3> points(const YAML::Node& n, const std::string& key, bool required = true) {
    const YAML::Node v = n[key];
    if (!v.IsDefined()) {
      if (required) c_.required(n, key);
      return {};
    }
    c_.expect_sequence(v, key);
    std::vector<Vec3> out;
    for (const auto& p : v) out.push_back(c_.as_vec3(p, key, ranges::coordinate));
    return out;
  }

  // A node named by id (`key`) or by position (`key_at`).
  NodeId node_ref(const YAML::Node& n, const std::string& key, const std::string& key_at) {
    const bool by_id = n[key].IsDefined(), by_pos = n[key_at].IsDefined();
    if (by_id == by_pos) c_.fail(n, key, "give exactly one of '" + key + "' (node id) and '" + key_at + "' (position)");
    if (by_id) return existing_node(n[key], key);
    return node_at(n[key_at], key_at);
  }
  NodeId existing_node(const YAML::Node& v, const std::string& key) {
    const NodeId id = c_.as_integer(v, key);
    if (!m_.has_node(id)) c_.fail(v, key, "node " + std::to_string(id) + " does not exist");
    return id;
  }
  NodeId node_at(const YAML::Node& v, const std::string& key) {
    const Vec3 x = c_.as_vec3(v, key, ranges::coordinate);
    fe::NodeMerger merger(m_, kNodeTolerance);
    if (auto id = merger.find(x)) return *id;
    c_.fail(v, key, "no node within 1e-6 m of this position");
  }
  // Nodes named by `nodes: [ids]`, `node`, `at`, `set: name`, or where they
  // are: `box: [[min], [max]]`, `line: [[a], [b]]` (on the segment),
  // `plane: [[point], [normal]]`, `near: [[point], distance]`.
  std::vector<NodeId> node_list(const YAML::Node& n, const std::string& nodes_key = "nodes") {
    const char* selectors[] = {"node", "at", "set", "box", "line", "plane", "near"};
    int given = n[nodes_key].IsDefined();
    for (const char* k : selectors) given += n[k].IsDefined();
    if (given != 1)
      c_.fail(n, nodes_key,
              "give exactly one of '" + nodes_key + "', 'node', 'at', 'set', 'box', 'line', 'plane' or 'near'");
    if (n["node"].IsDefined() || n["at"].IsDefined()) return {node_ref(n, "node", "at")};
    std::vector<NodeId> out;
    if (n[nodes_key].IsDefined()) {
      c_.expect_sequence(n[nodes_key], nodes_key);
      for (const auto& v : n[nodes_key]) out.push_back(existing_node(v, nodes_key));
    } else if (n["set"].IsDefined()) {
      const std::string name = c_.text(n, "set");
      auto it = m_.node_sets.find(name);
      if (it == m_.node_sets.end()) c_.fail(n["set"], "set", "node set '" + name + "' does not exist");
      out = it->second;
    } else {
      out = nodes_where(n);
    }
    return out;
  }
  // The geometric selectors. Their points are bounds of a selection, not
  // geometry, so they are not range-checked (+-1e9 for "everything along
  // x" is fine); nodes count as on a line or plane within kNodeTolerance.
  std::vector<NodeId> nodes_where(const YAML::Node& n) {
    auto pair = [&](const char* key, const char* form) {
      const YAML::Node v = n[key];
      if (!v.IsSequence() || v.size() != 2) c_.fail(v, key, std::string("expected ") + form);
      return v;
    };
    const char* key = "";
    std::vector<NodeId> out;
    if (n["box"].IsDefined()) {
      key = "box";
      const YAML::Node b = pair(key, "[[xmin, ymin, zmin], [xmax, ymax, zmax]]");
      out = fe::nodes_in_box(m_, c_.as_vec3(b[0], key), c_.as_vec3(b[1], key), kNodeTolerance);
    } else if (n["line"].IsDefined()) {
      key = "line";
      const YAML::Node l = pair(key, "[[x1, y1, z1], [x2, y2, z2]], the ends of a segment");
      const Vec3 a = c_.as_vec3(l[0], key), b = c_.as_vec3(l[1], key);
      if (!((b - a).norm() > kNodeTolerance)) c_.fail(l, key, "the segment's ends coincide");
      out = fe::nodes_on_segment(m_, a, b, kNodeTolerance);
    } else if (n["plane"].IsDefined()) {
      key = "plane";
      const YAML::Node p = pair(key, "[[x, y, z], [nx, ny, nz]], a point on the plane and its normal");
      const Vec3 normal = c_.as_vec3(p[1], key);
      if (!(normal.norm() > 0.0)) c_.fail(p[1], key, "the normal is zero");
      out = fe::nodes_on_plane(m_, c_.as_vec3(p[0], key), normal, kNodeTolerance);
    } else {
      key = "near";
      const YAML::Node p = pair(key, "[[x, y, z], distance]");
      const double distance = c_.as_number(p[1], key);
      if (!(distance >= 0.0)) c_.fail(p[1], key, "the distance must be zero or positive");
      out = fe::nodes_near(m_, c_.as_vec3(p[0], key), distance + kNodeTolerance);
    }
    if (out.empty()) c_.fail(n[key], key, std::string("no node selected by this ") + key);
    return out;
  }
  fe::DofMask dofs(const YAML::Node& n, const std::string& key, fe::DofMask fallback) {
    const YAML::Node v = n[key];
    if (!v.IsDefined()) return fallback;
    if (v.IsScalar()) {
      const std::string s = v.as<std::string>();
      if (s == "all") return {true, true, true, true, true, true};
      if (s == "translations") return {true, true, true, false, false, false};
      if (s == "rotations") return {false, false, false, true, true, true};
      c_.fail(v, key, "expected all, translations, rotations or a list of UX UY UZ RX RY RZ");
    }
    c_.expect_sequence(v, key);
    fe::DofMask mask{};
    for (const auto& d : v) {
      const std::string s = d.IsScalar() ? d.as<std::string>() : "";
      const std::optional<int> k = fe::dof_index(s);
      if (!k) c_.fail(d, key, "unknown DOF '" + s + "' (expected UX UY UZ RX RY RZ)");
      mask[static_cast<size_t>(*k)] = true;
    }
    return mask;
  }

  void material(const std::string& name, const YAML::Node& n) {
    c_.expect_map(n, "material '" + name + "'", {"E", "nu", "rho"});
    src_.add("material", name, n);
    m_.materials[name] = {name, c_.number(n, "E", ranges::youngs_modulus), c_.number(n, "nu"),
                          c_.number(n, "rho", ranges::density)};
  }
  void beam_section(const std::string& name, const YAML::Node& n) {
    c_.expect_map(n, "beam section '" + name + "'",
                  {"material", "shape", "width", "height", "diameter", "wall", "web_thickness", "flange_thickness",
                   "A", "Iy", "Iz", "J", "shear_area_y", "shear_area_z"});
    src_.add("beam_section", name, n);
    fe::BeamSection s;
    s.name = name;
    s.material = c_.text(n, "material");
    const std::string shape = c_.text(n, "shape");
    using fe::SectionShape;
    const std::map<std::string, SectionShape> shapes{{"rectangle", SectionShape::Rectangle},
                                                     {"circle", SectionShape::Circle},
                                                     {"box", SectionShape::Box},
                                                     {"tube", SectionShape::Tube},
                                                     {"i-section", SectionShape::ISection},
                                                     {"general", SectionShape::General}};
    auto it = shapes.find(shape);
    if (it == shapes.end()) c_.fail(n["shape"], "shape", "expected rectangle, circle, box, tube, i-section or general");
    s.shape = it->second;
    switch (s.shape) {
      case SectionShape::Rectangle:
        s.width = c_.number(n, "width", ranges::section_dimension);
        s.height = c_.number(n, "height", ranges::section_dimension);
        break;
      case SectionShape::Circle:
        s.diameter = c_.number(n, "diameter", ranges::section_dimension);
        break;
      case SectionShape::Tube:
        s.diameter = c_.number(n, "diameter", ranges::section_dimension);
        s.wall = c_.number(n, "wall", ranges::section_dimension);
        break;
      case SectionShape::Box:
        s.width = c_.number(n, "width", ranges::section_dimension);
        s.height = c_.number(n, "height", ranges::section_dimension);
        s.wall = c_.number_or(n, "wall", 0.0, ranges::section_dimension);
        s.web_thickness = c_.number_or(n, "web_thickness", 0.0, ranges::section_dimension);
        s.flange_thickness = c_.number_or(n, "flange_thickness", 0.0, ranges::section_dimension);
        if (!n["wall"].IsDefined() && !(n["web_thickness"].IsDefined() && n["flange_thickness"].IsDefined()))
          c_.fail(n, "wall", "a box needs 'wall' or both 'web_thickness' and 'flange_thickness'");
        break;
      case SectionShape::ISection:
        s.width = c_.number(n, "width", ranges::section_dimension);
        s.height = c_.number(n, "height", ranges::section_dimension);
        s.web_thickness = c_.number(n, "web_thickness", ranges::section_dimension);
        s.flange_thickness = c_.number(n, "flange_thickness", ranges::section_dimension);
        break;
      case SectionShape::General:
        s.A = c_.number(n, "A", ranges::area);
        s.Iy = c_.number(n, "Iy", ranges::second_moment);
        s.Iz = c_.number(n, "Iz", ranges::second_moment);
        s.J = c_.number(n, "J", ranges::second_moment);
        s.shear_area_y = c_.optional_number(n, "shear_area_y");
        s.shear_area_z = c_.optional_number(n, "shear_area_z");
        break;
    }
    m_.beam_sections[name] = s;
  }
  void shell_section(const std::string& name, const YAML::Node& n) {
    c_.expect_map(n, "shell section '" + name + "'", {"material", "thickness"});
    src_.add("shell_section", name, n);
    m_.shell_sections[name] = {name, c_.text(n, "material"), c_.number(n, "thickness", ranges::shell_thickness)};
  }
  void node(const YAML::Node& n) {
    if (!n.IsSequence() || n.size() != 4) c_.fail(n, index_, "a node is [id, x, y, z]");
    const NodeId id = c_.as_integer(n[0], "nodes");
    if (m_.has_node(id)) c_.fail(n, "nodes", "duplicate node id " + std::to_string(id));
    src_.add("node", std::to_string(id), n);
    const auto x = [&](int i) { return c_.as_number(n[i], "nodes", ranges::coordinate); };
    m_.add_node(id, {x(1), x(2), x(3)});
  }
  void beam(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "nodes", "section", "orientation", "theory", "mass", "rotary_inertia"});
    fe::BeamElement b;
    b.id = id_or_index(n);
    src_.add("beam", b.id, n);
    const YAML::Node nodes = c_.required(n, "nodes");
    if (!nodes.IsSequence() || nodes.size() != 2) c_.fail(nodes, "nodes", "a beam has 2 nodes");
    b.nodes = {c_.as_integer(nodes[0], "nodes"), c_.as_integer(nodes[1], "nodes")};
    b.section = c_.text(n, "section");
    if (n["orientation"].IsDefined()) b.orientation = c_.vec3(n, "orientation");
    b.theory = theory(n);
    b.mass = mass_kind(n);
    b.rotary_inertia = c_.boolean_or(n, "rotary_inertia", true);
    m_.beams.push_back(b);
  }
  void shell(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "nodes", "section", "mass"});
    fe::ShellElement s;
    s.id = id_or_index(n);
    src_.add("shell", s.id, n);
    const YAML::Node nodes = c_.required(n, "nodes");
    if (!nodes.IsSequence() || !fe::shell_type_with_nodes(nodes.size())) {
      std::string known;
      for (const fe::ShellType& t : fe::shell_types())
        known += std::string(known.empty() ? "" : " or ") + std::to_string(t.nodes) + " nodes (" + t.name + ")";
      c_.fail(nodes, "nodes", "a shell has " + known);
    }
    for (const auto& v : nodes) s.nodes.push_back(c_.as_integer(v, "nodes"));
    s.section = c_.text(n, "section");
    s.mass = mass_kind(n);
    m_.shells.push_back(s);
  }
  void solid(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "nodes", "material", "mass"});
    fe::SolidElement s;
    s.id = id_or_index(n);
    src_.add("solid", s.id, n);
    const YAML::Node nodes = c_.required(n, "nodes");
    if (!nodes.IsSequence() || !fe::solid_type_with_nodes(nodes.size()))
      c_.fail(nodes, "nodes", "a solid has " + fe::solid_node_counts() + " nodes (" + fe::solid_type_names() + ")");
    for (const auto& v : nodes) s.nodes.push_back(c_.as_integer(v, "nodes"));
    s.material = c_.text(n, "material");
    s.mass = mass_kind(n);
    m_.solids.push_back(s);
  }
  void solid_block(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "corners", "divisions", "element", "material", "mass"});
    fe::SolidBlockSpec s;
    s.id = id_or_index(n);
    const std::vector<Vec3> corners = points(n, "corners");
    if (corners.size() != 8) c_.fail(n["corners"], "corners", "a solid block has 8 corners (hex8 node order)");
    std::copy(corners.begin(), corners.end(), s.corners.begin());
    const YAML::Node d = c_.required(n, "divisions");
    if (!d.IsSequence() || d.size() != 3) c_.fail(d, "divisions", "expected three integers [n12, n14, n15]");
    s.nx = c_.as_count(d[0], "divisions", kMaxDivisions);
    s.ny = c_.as_count(d[1], "divisions", kMaxDivisions);
    s.nz = c_.as_count(d[2], "divisions", kMaxDivisions);
    s.element = c_.text_or(n, "element", s.element);
    if (!fe::solid_type_named(s.element)) c_.fail(n["element"], "element", "expected " + fe::solid_type_names());
    // Elements, with tet10's six per cell; a solid node has three DOFs and
    // a cell has 1 (hex8), 4 (hex20) or 8 (tet10: corner + 7 edges) nodes.
    const bool tet = s.element == "tet10";
    bounded_mesh(d, static_cast<double>(s.nx) * s.ny * s.nz * (tet ? 6 : 1),
                 tet                    ? 3.0 * 8.0 / 6.0
                 : s.element == "hex20" ? 12.0
                                        : 3.0);
    s.material = c_.text(n, "material");
    s.mass = mass_kind(n);
    generated(n, s.id, [&] {
      fe::NodeMerger merger(m_, kNodeTolerance);
      fe::mesh_solid_block(m_, merger, s);
    });
  }
  void member(const YAML::Node& n) {
    c_.expect_map(n, index_,
                  {"id", "from", "to", "elements", "section", "orientation", "theory", "mass", "rotary_inertia"});
    fe::MemberSpec s;
    s.id = id_or_index(n);
    s.from = c_.vec3(n, "from", ranges::coordinate);
    s.to = c_.vec3(n, "to", ranges::coordinate);
    s.elements = c_.as_count(c_.required(n, "elements"), "elements", kMaxDivisions);
    s.section = c_.text(n, "section");
    if (n["orientation"].IsDefined()) s.orientation = c_.vec3(n, "orientation");
    s.theory = theory(n);
    s.mass = mass_kind(n);
    s.rotary_inertia = c_.boolean_or(n, "rotary_inertia", true);
    generated(n, s.id, [&] {
      fe::NodeMerger merger(m_, kNodeTolerance);
      fe::mesh_member(m_, merger, s);
    });
  }
  void patch(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "corners", "divisions", "order", "section", "mass"});
    fe::PatchSpec s;
    s.id = id_or_index(n);
    const std::vector<Vec3> corners = points(n, "corners");
    if (corners.size() != 4) c_.fail(n["corners"], "corners", "a patch has 4 corners");
    std::copy(corners.begin(), corners.end(), s.corners.begin());
    std::tie(s.nx, s.ny) = pair_of_ints(n, "divisions");
    s.quadratic = quadratic(n);
    // A shell node has six DOFs; an 8-node element brings three nodes, a 4-node one.
    bounded_mesh(n["divisions"], static_cast<double>(s.nx) * s.ny, s.quadratic ? 18.0 : 6.0);
    s.section = c_.text(n, "section");
    s.mass = mass_kind(n);
    generated(n, s.id, [&] {
      fe::NodeMerger merger(m_, kNodeTolerance);
      fe::mesh_shell_patch(m_, merger, s);
    });
  }
  void box_girder(const YAML::Node& n) {
    c_.expect_map(n, index_,
                  {"id", "from", "to", "up", "width", "height", "web_thickness", "flange_thickness", "material",
                   "divisions", "order", "end_plates", "end_couplings", "mass"});
    fe::BoxGirderSpec s;
    s.id = id_or_index(n);
    s.from = c_.vec3(n, "from", ranges::coordinate);
    s.to = c_.vec3(n, "to", ranges::coordinate);
    if (n["up"].IsDefined()) s.up = c_.vec3(n, "up");
    s.width = c_.number(n, "width", ranges::section_dimension);
    s.height = c_.number(n, "height", ranges::section_dimension);
    s.web_thickness = c_.number(n, "web_thickness", ranges::section_dimension);
    s.flange_thickness = c_.number(n, "flange_thickness", ranges::section_dimension);
    s.material = c_.text(n, "material");
    const YAML::Node d = c_.required(n, "divisions");
    if (!d.IsSequence() || d.size() != 3) c_.fail(d, "divisions", "expected [along, across width, across height]");
    s.n_along = c_.as_count(d[0], "divisions", kMaxDivisions);
    s.n_width = c_.as_count(d[1], "divisions", kMaxDivisions);
    s.n_height = c_.as_count(d[2], "divisions", kMaxDivisions);
    s.quadratic = quadratic(n);
    bounded_mesh(d, 2.0 * s.n_along * (s.n_width + s.n_height), s.quadratic ? 18.0 : 6.0);
    s.end_plates = c_.boolean_or(n, "end_plates", true);
    s.end_couplings = c_.boolean_or(n, "end_couplings", true);
    s.mass = mass_kind(n);
    generated(n, s.id, [&] {
      fe::NodeMerger merger(m_, kNodeTolerance);
      fe::mesh_box_girder(m_, merger, s);
      src_.add("shell_section", s.id + ".web", n);
      src_.add("shell_section", s.id + ".flange", n);
    });
  }
  // A Gmsh mesh (io/gmsh_mesh.hpp), its path relative to the model file;
  // `shells` and `solids` place its physical groups.
  void mesh(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "file", "shells", "solids", "mass"});
    GmshPlacement p;
    p.id = id_or_index(n);
    p.mass = mass_kind(n);
    const std::string name = c_.text(n, "file");
    const std::filesystem::path path = std::filesystem::path(c_.file()).parent_path() / name;
    if (path.extension() != ".msh") c_.fail(n["file"], "file", "expected a Gmsh mesh (.msh)");
    const GmshMesh mesh = read_gmsh(path);
    auto place = [&](const char* key, int dim, std::map<std::string, std::string>& out, const auto& known,
                     const char* what) {
      const YAML::Node g = n[key];
      if (!g.IsDefined()) return;
      if (!g.IsMap() || g.size() == 0) c_.fail(g, key, std::string("expected {physical group: ") + what + ", ...}");
      for (const auto& kv : g) {
        if (!kv.first.IsScalar() || !kv.second.IsScalar())
          c_.fail(g, key, std::string("expected {physical group: ") + what + ", ...}");
        const std::string group = kv.first.as<std::string>(), target = kv.second.as<std::string>();
        if (gmsh_group(mesh, dim, group) < 0)
          c_.fail(kv.first, key,
                  "no " + std::string(dim == 2 ? "surface" : "volume") + " physical group '" + group + "' in " +
                      path.string());
        if (!known.count(target)) c_.fail(kv.second, key, std::string(what) + " '" + target + "' does not exist");
        out[group] = target;
      }
    };
    place("shells", 2, p.shells, m_.shell_sections, "shell section");
    place("solids", 3, p.solids, m_.materials, "material");
    if (p.shells.empty() && p.solids.empty())
      c_.fail(n, "shells", "place at least one physical group (shells or solids)");
    generated(n, p.id, [&] { add_gmsh_mesh(m_, mesh, p, path.string()); });
  }
  // A reduced frame (a folder `rigflex reduce --export` wrote) placed where
  // its interface nodes are: each meets the model's node at its position
  // (1e-6 m), or becomes a node of its own.
  void superelement(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "reduced"});
    fe::Superelement e;
    e.id = id_or_index(n);
    const std::filesystem::path dir = std::filesystem::path(c_.file()).parent_path() / c_.text(n, "reduced");
    if (!std::filesystem::is_directory(dir)) c_.fail(n["reduced"], "reduced", "no such folder: " + dir.string());
    reduction::ReducedFrame r;
    try {
      r = read_reduced_frame(dir);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& x) {
      c_.fail(n["reduced"], "reduced", x.what());
    }
    std::map<fe::NodeId, fe::NodeId> placed;
    fe::Vec3 centre = fe::Vec3::Zero();
    for (const reduction::InterfaceNode& node : r.interface_nodes) {
      const std::vector<fe::NodeId> there = fe::nodes_near(m_, node.position, 1e-6);
      if (there.size() > 1)
        c_.fail(n["reduced"], "reduced",
                "interface node " + std::to_string(node.id) + " meets " + std::to_string(there.size()) +
                    " model nodes at its position");
      placed[node.id] = there.empty() ? m_.add_node(m_.has_node(node.id) ? m_.next_node_id() : node.id, node.position)
                                      : there.front();
      centre += node.position / static_cast<double>(r.interface_nodes.size());
    }
    for (const reduction::InterfaceDof& d : r.interface_dofs) e.interface.push_back({placed.at(d.node), d.local});
    e.K = std::move(r.K);
    e.M = std::move(r.M);
    e.grounded = r.support == reduction::FrameSupport::grounded;
    src_.add("superelement", e.id, n);
    pending_.push_back({std::move(e), r.mode_count, centre});
  }
  // Last, so that no selector of the file ever takes a modal node.
  void add_modal_nodes() {
    for (Pending& p : pending_) {
      for (int k = 0; k < p.modes; ++k) p.element.modal_nodes.push_back(m_.add_node(m_.next_node_id(), p.centre));
      m_.superelements.push_back(std::move(p.element));
    }
    pending_.clear();
  }
  void fixed_frame(const YAML::Node& n) {
    index_ = "fixed_frame";
    c_.expect_map(n, "fixed_frame",
                  {"id", "column_bases", "height", "column_section", "beam_section", "extra_beams", "ring", "joints",
                   "elements_per_member", "joint_set"});
    fe::FixedFrameSpec s;
    s.id = c_.text_or(n, "id", s.id);
    s.column_bases = points(n, "column_bases");
    s.height = c_.number(n, "height", ranges::length);
    s.column_section = c_.text(n, "column_section");
    s.beam_section = c_.text(n, "beam_section");
    if (n["extra_beams"].IsDefined()) {
      c_.expect_sequence(n["extra_beams"], "extra_beams");
      for (const auto& p : n["extra_beams"]) {
        if (!p.IsSequence() || p.size() != 2) c_.fail(p, "extra_beams", "expected pairs of column numbers [i, j]");
        s.extra_beams.push_back({static_cast<int>(c_.as_integer(p[0], "extra_beams")) - 1,
                                 static_cast<int>(c_.as_integer(p[1], "extra_beams")) - 1});
      }
    }
    s.ring = c_.boolean_or(n, "ring", true);
    s.joints = points(n, "joints");
    if (n["elements_per_member"].IsDefined()) {
      s.elements_per_member = c_.as_count(n["elements_per_member"], "elements_per_member", kMaxDivisions);
    }
    s.joint_set = c_.text_or(n, "joint_set", s.joint_set);
    generated(n, s.id, [&] { fe::build_fixed_frame(m_, s); });
  }
  void carrying_frame(const YAML::Node& n) {
    index_ = "carrying_frame";
    c_.expect_map(n, "carrying_frame",
                  {"id", "corner_min", "corner_max", "bays", "section", "joints", "elements_per_member", "joint_set"});
    fe::CarryingFrameSpec s;
    s.id = c_.text_or(n, "id", s.id);
    s.corner_min = c_.vec3(n, "corner_min", ranges::coordinate);
    s.corner_max = c_.vec3(n, "corner_max", ranges::coordinate);
    std::tie(s.bays_x, s.bays_y) = pair_of_ints(n, "bays");
    s.section = c_.text(n, "section");
    s.joints = points(n, "joints");
    if (n["elements_per_member"].IsDefined()) {
      s.elements_per_member = c_.as_count(n["elements_per_member"], "elements_per_member", kMaxDivisions);
    }
    s.joint_set = c_.text_or(n, "joint_set", s.joint_set);
    generated(n, s.id, [&] { fe::build_carrying_frame(m_, s); });
  }
  // Mesher errors, and errors later found in the entities a generator made,
  // point at the generator's entry.
  template <class F>
  void generated(const YAML::Node& n, const std::string& id, F f) {
    const size_t beams0 = m_.beams.size(), shells0 = m_.shells.size(), solids0 = m_.solids.size(),
                 couplings0 = m_.couplings.size(), supports0 = m_.supports.size();
    try {
      f();
    } catch (const fe::ModelError& e) {
      const YAML::Node at = n[e.where().key].IsDefined() ? n[e.where().key] : n;
      c_.fail(at, e.where().key.empty() ? id : e.where().key, e.what());
    }
    for (size_t i = beams0; i < m_.beams.size(); ++i) src_.add("beam", m_.beams[i].id, n);
    for (size_t i = shells0; i < m_.shells.size(); ++i) src_.add("shell", m_.shells[i].id, n);
    for (size_t i = solids0; i < m_.solids.size(); ++i) src_.add("solid", m_.solids[i].id, n);
    for (size_t i = couplings0; i < m_.couplings.size(); ++i) src_.add("coupling", m_.couplings[i].id, n);
    for (size_t i = supports0; i < m_.supports.size(); ++i) src_.add("support", m_.supports[i].id, n);
  }
  void node_set(const std::string& name, const YAML::Node& n) {
    index_ = "node_sets." + name;
    src_.add("node_set", name, n);
    if (n.IsSequence()) {
      std::vector<NodeId> ids;
      for (const auto& v : n) ids.push_back(existing_node(v, name));
      m_.node_sets[name] = ids;
      return;
    }
    c_.expect_map(n, "node set '" + name + "'", {"nodes", "set", "box", "line", "plane", "near", "node", "at"});
    m_.node_sets[name] = node_list(n);
  }
  // Elements by id, or every beam, shell and solid whose nodes all lie in a
  // node selection (a node set, or box / line / plane / near).
  void element_set(const std::string& name, const YAML::Node& n) {
    src_.add("element_set", name, n);
    c_.expect_map(n, "element set '" + name + "'", {"elements", "set", "box", "line", "plane", "near"});
    int given = 0;
    for (const char* k : {"elements", "set", "box", "line", "plane", "near"}) given += n[k].IsDefined();
    if (given != 1) c_.fail(n, "elements", "give exactly one of 'elements', 'set', 'box', 'line', 'plane' or 'near'");
    std::vector<ElementRef> out;
    if (n["elements"].IsDefined()) {
      c_.expect_sequence(n["elements"], "elements");
      std::unordered_map<std::string, std::vector<ElementRef>> by_id;
      for (size_t i = 0; i < m_.beams.size(); ++i) by_id[m_.beams[i].id].push_back({'b', i});
      for (size_t i = 0; i < m_.shells.size(); ++i) by_id[m_.shells[i].id].push_back({'s', i});
      for (size_t i = 0; i < m_.solids.size(); ++i) by_id[m_.solids[i].id].push_back({'v', i});
      for (const auto& v : n["elements"]) {
        if (!v.IsScalar()) c_.fail(v, "elements", "expected element ids");
        const std::string id = v.as<std::string>();
        const auto hit = by_id.find(id);
        const std::vector<ElementRef> found = hit == by_id.end() ? std::vector<ElementRef>{} : hit->second;
        if (found.size() != 1)
          c_.fail(v, "elements",
                  found.empty() ? "no beam, shell or solid '" + id + "'" : "'" + id + "' names elements of two kinds");
        out.push_back(found.front());
      }
    } else {
      const std::vector<NodeId> ids = node_list(n);
      const std::set<NodeId> chosen(ids.begin(), ids.end());
      auto inside = [&](const auto& nodes) {
        return std::all_of(nodes.begin(), nodes.end(), [&](NodeId id) { return chosen.count(id) != 0; });
      };
      for (size_t i = 0; i < m_.beams.size(); ++i)
        if (inside(m_.beams[i].nodes)) out.push_back({'b', i});
      for (size_t i = 0; i < m_.shells.size(); ++i)
        if (inside(m_.shells[i].nodes)) out.push_back({'s', i});
      for (size_t i = 0; i < m_.solids.size(); ++i)
        if (inside(m_.solids[i].nodes)) out.push_back({'v', i});
      if (out.empty()) c_.fail(n, "element_sets", "element set '" + name + "': no element has all its nodes selected");
    }
    element_sets_[name] = out;
  }
  // A section, material or mass kind given to the elements of a set.
  void assignment(const YAML::Node& n) {
    c_.expect_map(n, index_, {"set", "section", "material", "mass"});
    const std::string name = c_.text(n, "set");
    const auto it = element_sets_.find(name);
    if (it == element_sets_.end()) c_.fail(n["set"], "set", "element set '" + name + "' does not exist");
    const bool section = n["section"].IsDefined(), material = n["material"].IsDefined(), mass = n["mass"].IsDefined();
    if (!section && !material && !mass) c_.fail(n, "section", "give a section, a material or a mass kind");
    const std::string s = section ? c_.text(n, "section") : "", mat = material ? c_.text(n, "material") : "";
    const fe::MassKind kind = mass_kind(n);
    for (const ElementRef& e : it->second) {
      if (e.kind == 'b' && section && !m_.beam_sections.count(s))
        c_.fail(n["section"], "section", "the set holds beams and there is no beam section '" + s + "'");
      if (e.kind == 's' && section && !m_.shell_sections.count(s))
        c_.fail(n["section"], "section", "the set holds shells and there is no shell section '" + s + "'");
      if (e.kind == 'v' && !section && material && !m_.materials.count(mat))
        c_.fail(n["material"], "material", "material '" + mat + "' does not exist");
      if (e.kind == 'v' && section) c_.fail(n["section"], "section", "the set holds solids: give them a material");
      if (e.kind != 'v' && material)
        c_.fail(n["material"], "material", "the set holds beams or shells: give them a section");
    }
    for (const ElementRef& e : it->second) {
      if (e.kind == 'b') {
        if (section) m_.beams[e.index].section = s;
        if (mass) m_.beams[e.index].mass = kind;
      } else if (e.kind == 's') {
        if (section) m_.shells[e.index].section = s;
        if (mass) m_.shells[e.index].mass = kind;
      } else {
        if (material) m_.solids[e.index].material = mat;
        if (mass) m_.solids[e.index].mass = kind;
      }
    }
  }
  void point_mass(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "node", "at", "mass", "inertia"});
    fe::PointMass p;
    p.id = id_or_index(n);
    src_.add("point_mass", p.id, n);
    p.node = node_ref(n, "node", "at");
    p.mass = c_.number(n, "mass", ranges::point_mass);
    if (n["inertia"].IsDefined()) {
      const auto J = c_.numbers(n, "inertia", 6, ranges::inertia);
      std::copy(J.begin(), J.end(), p.inertia.begin());
    }
    m_.point_masses.push_back(p);
  }
  void spring(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "node", "at", "other", "other_at", "stiffness", "axial", "direction"});
    fe::Spring s;
    s.id = id_or_index(n);
    src_.add("spring", s.id, n);
    s.node = node_ref(n, "node", "at");
    if (n["other"].IsDefined() || n["other_at"].IsDefined()) s.other = node_ref(n, "other", "other_at");
    if (n["stiffness"].IsDefined() == n["axial"].IsDefined())
      c_.fail(n, "stiffness", "give exactly one of 'stiffness' (6 values) and 'axial'");
    if (n["stiffness"].IsDefined()) {
      const auto k = c_.numbers(n, "stiffness", 6);
      std::copy(k.begin(), k.end(), s.stiffness.begin());
    } else {
      s.axial = c_.number(n, "axial");
      if (n["direction"].IsDefined()) s.direction = c_.vec3(n, "direction");
    }
    m_.springs.push_back(s);
  }
  void support(const YAML::Node& n) {
    c_.expect_map(n, index_, {"id", "node", "at", "nodes", "set", "box", "line", "plane", "near", "dofs"});
    const std::string id = id_or_index(n);
    const fe::DofMask mask = dofs(n, "dofs", {true, true, true, true, true, true});
    for (NodeId node : node_list(n)) {
      const std::string sid = id + "@" + std::to_string(node);
      src_.add("support", sid, n);
      m_.supports.push_back({sid, node, mask});
    }
  }
  void coupling(const YAML::Node& n) {
    c_.expect_map(
        n, index_,
        {"id", "kind", "reference", "reference_at", "nodes", "set", "box", "line", "plane", "near", "dofs", "weights"});
    const std::string kind = c_.text_or(n, "kind", "rigid");
    if (kind != "rigid" && kind != "distributing") c_.fail(n["kind"], "kind", "expected rigid or distributing");
    if (kind == "distributing") return distributing_coupling(n);
    if (n["weights"].IsDefined()) c_.fail(n["weights"], "weights", "weights belong to a distributing coupling");
    fe::RigidCoupling r;
    r.id = id_or_index(n);
    src_.add("coupling", r.id, n);
    r.reference = node_ref(n, "reference", "reference_at");
    r.dependents = node_list(n);
    r.dofs = dofs(n, "dofs", r.dofs);
    m_.couplings.push_back(r);
  }
  void distributing_coupling(const YAML::Node& n) {
    if (n["dofs"].IsDefined())
      c_.fail(n["dofs"], "dofs", "a distributing coupling drives all six DOFs of its reference; no dofs to choose");
    fe::DistributingCoupling d;
    d.id = id_or_index(n);
    src_.add("coupling", d.id, n);
    d.reference = node_ref(n, "reference", "reference_at");
    d.nodes = node_list(n);
    if (n["weights"].IsDefined()) {
      c_.expect_sequence(n["weights"], "weights");
      for (const auto& v : n["weights"]) d.weights.push_back(c_.as_number(v, "weights"));
    }
    m_.distributing_couplings.push_back(d);
  }

  const YamlContext& c_;
  fe::Model& m_;
  SourceMap& src_;
  std::string index_;
};

}  // namespace

namespace {

ModelFile parse_model_unguarded(const std::string& text, const std::string& source) {
  const YamlContext ctx(source);
  const YAML::Node root = load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source, 1, "", "a model file is a mapping of sections (materials, nodes, ...)");
  ModelFile out;
  SourceMap src(source);
  try {
    ModelFileReader(ctx, out.model, src).read(root);
    out.model.validate();
    fe::check_element_matrices(out.model);
  } catch (const fe::ModelError& e) {
    const YAML::Node at = src.find(e.where());
    throw InputError(source, at.IsDefined() ? YamlContext::line_of(at) : 0,
                     e.where().key.empty() ? e.where().kind : e.where().key, e.what());
  }
  if (out.model.nodes.empty()) throw InputError(source, 1, "nodes", "the model has no nodes");
  out.name = root["name"].IsDefined() ? ctx.text(root, "name") : std::filesystem::path(source).stem().string();
  return out;
}

}  // namespace

ModelFile parse_model(const std::string& text, const std::string& source) {
  return guard_yaml(source, [&] { return parse_model_unguarded(text, source); });
}

}  // namespace rigflex::io
