#include "io/abaqus_deck.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>

#include "fe/element_loop.hpp"
#include "fe/error.hpp"
#include "fe/shell_centres.hpp"
#include "io/abaqus_cards.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {
namespace {

enum class Category { beam, shell, solid, mass, rotary, spring };

struct ElementType {
  const char* name;
  int nodes;
  Category category;
};

// Abaqus names; the node orders of S4/S8 and C3D8/C3D20/C3D10 are rigflex's
// (corners, then mid-edges in the same edge order), so nodes are taken as
// they stand. B32 elements become two rigflex beams split at their middle
// node.
constexpr ElementType kElementTypes[] = {
    {"B31", 2, Category::beam},       {"B31R", 2, Category::beam},      {"B32", 3, Category::beam},
    {"B32R", 3, Category::beam},      {"S4", 4, Category::shell},       {"S4R", 4, Category::shell},
    {"S8", 8, Category::shell},       {"S8R", 8, Category::shell},      {"C3D8", 8, Category::solid},
    {"C3D8I", 8, Category::solid},    {"C3D8R", 8, Category::solid},    {"C3D20", 20, Category::solid},
    {"C3D20R", 20, Category::solid},  {"C3D10", 10, Category::solid},   {"MASS", 1, Category::mass},
    {"ROTARYI", 1, Category::rotary}, {"SPRING1", 1, Category::spring}, {"SPRING2", 2, Category::spring},
    {"SPRINGA", 2, Category::spring},
};

const ElementType* element_type(const std::string& name) {
  for (const ElementType& t : kElementTypes)
    if (name == t.name) return &t;
  return nullptr;
}

std::string supported_types() {
  std::string s;
  for (const ElementType& t : kElementTypes) s += (s.empty() ? "" : ", ") + std::string(t.name);
  return s;
}

// Why a type rigflex does not take is refused, where there is more to say.
std::string refusal(const std::string& type) {
  if (type == "S3" || type == "S3R" || type == "STRI3" || type == "STRI65" || type == "S6")
    return "rigflex has no triangular shell element: mesh the surface with quadrilaterals (S4 or S8R)";
  if (type == "C3D4") return "a linear tetrahedron is far too stiff in bending: mesh with C3D10";
  if (type == "C3D6" || type == "C3D15") return "rigflex has no wedge element: mesh with hexahedra or C3D10";
  if (type.rfind("T3D", 0) == 0) return "truss elements: use B31 with a section, or SPRINGA for an axial link";
  return "rigflex takes " + supported_types();
}

struct Element {
  const ElementType* type = nullptr;
  std::vector<long> nodes;
  DeckWhere at;
  int property = -1;  // index into DeckReader::properties_
};

// A section, mass, rotary inertia or spring card and what it gives its elements.
struct Property {
  Category category = Category::beam;
  DeckWhere at;
  std::string name;                  // the model's section / material name
  fe::Vec3 n1 = fe::Vec3(0, 0, -1);  // beams: Abaqus's default 1-direction
  std::vector<double> values;        // masses, inertias, spring data
  int dof1 = 0, dof2 = 0;            // springs
};

struct Material {
  std::string name;
  DeckWhere at;
  std::optional<double> E, nu, rho;
};

class DeckReader {
 public:
  explicit DeckReader(std::vector<DeckCard> cards, std::string source)
      : cards_(std::move(cards)), source_(std::move(source)) {}

  ModelFile read() {
    // Materials first: decks name them in sections before defining them.
    for (const DeckCard& c : cards_) material_card(c);
    for (i_ = 0; i_ < cards_.size(); ++i_) model_card(cards_[i_]);
    build_elements();
    build_supports();
    fe::add_shell_centres(m_);
    ModelFile out;
    out.model = std::move(m_);
    out.name = name_.empty() ? std::filesystem::path(source_).stem().string() : name_;
    try {
      out.model.validate();
      fe::check_element_matrices(out.model);
    } catch (const fe::ModelError& e) {
      const auto it = where_.find(e.where().kind + ":" + e.where().id);
      const DeckWhere at = it != where_.end() ? it->second : DeckWhere{source_, 0};
      throw InputError(at.file, at.line, e.where().key.empty() ? e.where().kind : e.where().key, e.what());
    }
    if (out.model.nodes.empty()) throw InputError(source_, 0, "*NODE", "the deck defines no nodes");
    return out;
  }

 private:
  // ---- errors and fields -------------------------------------------------
  [[noreturn]] static void fail(const DeckWhere& at, const std::string& key, const std::string& message) {
    throw InputError(at.file, at.line, key, message);
  }
  static std::string key(const DeckCard& c) { return "*" + c.keyword; }

  static double number(const DeckDataLine& l, size_t k, const DeckCard& c, const char* what) {
    if (k >= l.fields.size() || l.fields[k].empty())
      fail(l.at, key(c), std::string(what) + " expected in field " + std::to_string(k + 1));
    std::string s = l.fields[k];
    std::replace(s.begin(), s.end(), 'D', 'E');  // Fortran's 1.0D3
    std::replace(s.begin(), s.end(), 'd', 'e');
    if (!s.empty() && s.front() == '+') s.erase(0, 1);
    double v = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
      fail(l.at, key(c), std::string(what) + ": '" + l.fields[k] + "' is not a finite number");
    return v;
  }
  static double number_or(const DeckDataLine& l, size_t k, const DeckCard& c, const char* what, double dflt) {
    return k < l.fields.size() && !l.fields[k].empty() ? number(l, k, c, what) : dflt;
  }
  static std::optional<long> integer(const std::string& s) {
    long v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
    return v;
  }
  static long label(const DeckDataLine& l, size_t k, const DeckCard& c, const char* what) {
    if (k >= l.fields.size()) fail(l.at, key(c), std::string(what) + " expected in field " + std::to_string(k + 1));
    const auto v = integer(l.fields[k]);
    if (!v || *v < 1) fail(l.at, key(c), std::string(what) + ": '" + l.fields[k] + "' is not a positive integer");
    return *v;
  }
  static const std::string& param(const DeckCard& c, const std::string& name) {
    const auto it = c.params.find(name);
    if (it == c.params.end() || it->second.empty()) fail(c.at, key(c), name + "= is required");
    return it->second;
  }
  // Parameters other than `known` are refused: each one changes what the card means.
  static void only(const DeckCard& c, std::initializer_list<const char*> known) {
    for (const auto& param : c.params) {
      const std::string& name = param.first;
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return name == k; }))
        fail(c.at, key(c), "parameter " + name + " is not supported here");
    }
  }
  static const DeckDataLine& first_line(const DeckCard& c, const char* what) {
    if (c.data.empty()) fail(c.at, key(c), std::string("a data line with ") + what + " is required");
    return c.data.front();
  }

  // ---- cards ---------------------------------------------------------------
  void material_card(const DeckCard& c) {
    const std::string& k = c.keyword;
    if (k == "MATERIAL") return material(c);
    if (k == "ELASTIC") return elastic(c);
    if (k == "DENSITY") return density(c);
    material_ = nullptr;
  }

  void model_card(const DeckCard& c) {
    const std::string& k = c.keyword;
    if (k == "MATERIAL" || k == "ELASTIC" || k == "DENSITY") return;  // read first
    if (k != "TRANSVERSE SHEAR STIFFNESS") general_section_ = -1;
    if (in_step_) return step_card(c);
    if (k == "HEADING") return heading(c);
    if (k == "PREPRINT") return;  // printing options of the solver's own run
    if (k == "NODE") return nodes(c);
    if (k == "ELEMENT") return elements(c);
    if (k == "NSET") return node_set(c);
    if (k == "ELSET") return element_set(c);
    if (k == "BEAM SECTION") return beam_section(c);
    if (k == "BEAM GENERAL SECTION") return beam_general_section(c);
    if (k == "TRANSVERSE SHEAR STIFFNESS") return transverse_shear(c);
    if (k == "SHELL SECTION") return shell_section(c);
    if (k == "SOLID SECTION") return solid_section(c);
    if (k == "MASS") return mass(c);
    if (k == "ROTARY INERTIA") return rotary_inertia(c);
    if (k == "SPRING") return spring(c);
    if (k == "BOUNDARY") return boundary(c);
    if (k == "RIGID BODY") return rigid_body(c);
    if (k == "SURFACE") return surface(c);
    if (k == "COUPLING") return coupling(c);
    if (k == "STEP") {
      only(c, {"NAME", "NLGEOM", "PERTURBATION", "INC"});
      in_step_ = true;
      return;
    }
    unsupported(c);
  }

  [[noreturn]] void unsupported(const DeckCard& c) const {
    const std::string& k = c.keyword;
    std::string why = "is not supported by rigflex's deck reader";
    if (k == "PART" || k == "INSTANCE" || k == "ASSEMBLY" || k == "END PART" || k == "END INSTANCE")
      why +=
          ": parts and instances are not read; write the model as a flat deck (Abaqus/CAE: "
          "Model > Edit Attributes, or 'Do not use parts and assemblies in input files')";
    else if (k == "EQUATION" || k == "MPC")
      why += ": linear constraints other than *RIGID BODY and *COUPLING are not read";
    else if (k == "ORIENTATION" || k == "TRANSFORM" || k == "SYSTEM")
      why += ": local coordinate systems are not read; give coordinates and boundary conditions in global axes";
    else if (k == "CLOAD" || k == "DLOAD" || k == "DSLOAD" || k == "TEMPERATURE" || k == "AMPLITUDE")
      why += ": rigflex computes modes and reduced matrices; loads are not part of its model";
    else if (k == "PLASTIC" || k == "EXPANSION" || k == "CONDUCTIVITY" || k == "SPECIFIC HEAT" || k == "DAMPING")
      why += ": materials are linear elastic with *ELASTIC and *DENSITY only; remove it for a modal model";
    fail(c.at, key(c), "*" + k + " " + why);
  }

  void step_card(const DeckCard& c) {
    const std::string& k = c.keyword;
    if (k == "END STEP") {
      in_step_ = false;
      return;
    }
    if (k == "FREQUENCY") {
      only(c, {"SOLVER", "STORAGE", "MATRIXSTORAGE", "GLOBAL", "CYCMPC", "EIGENSOLVER", "NORMALIZATION"});
      return;  // the number of modes is chosen on rigflex's command line
    }
    if (k == "BOUNDARY") return boundary(c);
    if (k == "NODE FILE" || k == "EL FILE" || k == "NODE PRINT" || k == "EL PRINT" || k == "NODE OUTPUT" ||
        k == "ELEMENT OUTPUT" || k == "OUTPUT" || k == "FIELD OUTPUT")
      return;  // output requests of the solver's own run
    if (k == "STATIC" || k == "DYNAMIC" || k == "BUCKLE" || k == "STEADY STATE DYNAMICS" || k == "MODAL DYNAMIC")
      fail(c.at, key(c),
           "*" + k +
               " step: rigflex reads the model data and the boundary conditions of *FREQUENCY steps; "
               "make the step a *FREQUENCY step or remove it");
    unsupported(c);
  }

  void heading(const DeckCard& c) {
    if (!name_.empty() || c.data.empty()) return;
    name_ = c.data.front().text;
  }

  void nodes(const DeckCard& c) {
    only(c, {"NSET"});
    std::vector<long> added;
    for (const DeckDataLine& l : c.data) {
      const long id = label(l, 0, c, "node label");
      if (l.fields.size() > 4) fail(l.at, key(c), "a node line is: label, x, y, z");
      const fe::Vec3 x(number_or(l, 1, c, "x", 0.0), number_or(l, 2, c, "y", 0.0), number_or(l, 3, c, "z", 0.0));
      if (m_.has_node(id)) fail(l.at, key(c), "node " + std::to_string(id) + " is defined twice");
      // Units are the deck's own, but no structure is 1e15 of them across.
      if (x.cwiseAbs().maxCoeff() > 1e15) fail(l.at, key(c), "a coordinate beyond 1e15 is not a position");
      m_.add_node(id, x);
      where_["node:" + std::to_string(id)] = l.at;
      added.push_back(id);
    }
    if (c.has("NSET")) add_to_set(node_sets_, param(c, "NSET"), added);
  }

  void elements(const DeckCard& c) {
    only(c, {"TYPE", "ELSET"});
    const std::string type_name = deck_upper(param(c, "TYPE"));
    const ElementType* type = element_type(type_name);
    if (!type) fail(c.at, "TYPE", "element type " + type_name + ": " + refusal(type_name));
    std::vector<long> added;
    // An element's labels may continue on the next line after a trailing comma.
    std::vector<std::string> fields;
    DeckWhere at;
    for (const DeckDataLine& l : c.data) {
      if (fields.empty()) at = l.at;
      fields.insert(fields.end(), l.fields.begin(), l.fields.end());
      if (static_cast<int>(fields.size()) < type->nodes + 1) continue;
      const DeckDataLine whole{at, fields, ""};
      if (static_cast<int>(fields.size()) > type->nodes + 1)
        fail(at, key(c),
             std::string(type->name) + " has " + std::to_string(type->nodes) + " nodes, the line gives " +
                 std::to_string(fields.size() - 1));
      const long id = label(whole, 0, c, "element label");
      if (elements_.count(id)) fail(at, key(c), "element " + std::to_string(id) + " is defined twice");
      Element e;
      e.type = type;
      e.at = at;
      for (int n = 1; n <= type->nodes; ++n) {
        const long node = label(whole, static_cast<size_t>(n), c, "node label");
        if (!m_.has_node(node))
          fail(at, key(c),
               "element " + std::to_string(id) + " names node " + std::to_string(node) +
                   ", which no *NODE defined before it");
        e.nodes.push_back(node);
      }
      elements_[id] = std::move(e);
      added.push_back(id);
      fields.clear();
    }
    if (!fields.empty())
      fail(at, key(c),
           std::string(type->name) + " has " + std::to_string(type->nodes) + " nodes; the card ends after " +
               std::to_string(fields.size() - 1));
    if (c.has("ELSET")) add_to_set(element_sets_, param(c, "ELSET"), added);
  }

  // ---- sets ------------------------------------------------------------------
  struct Set {
    std::string name;  // as first written
    std::vector<long> labels;
  };
  using Sets = std::map<std::string, Set>;  // by upper-case name

  static void add_to_set(Sets& sets, const std::string& name, const std::vector<long>& labels) {
    Set& s = sets[deck_upper(name)];
    if (s.name.empty()) s.name = name;
    s.labels.insert(s.labels.end(), labels.begin(), labels.end());
  }

  // The labels of a data line: numbers, or names of sets defined before.
  std::vector<long> set_members(const DeckCard& c, bool nodes) const {
    const Sets& sets = nodes ? node_sets_ : element_sets_;
    const size_t defined = nodes ? m_.nodes.size() : elements_.size();
    const char* what = nodes ? "node" : "element";
    std::vector<long> out;
    for (const DeckDataLine& l : c.data) {
      if (c.has("GENERATE")) {
        const long first = label(l, 0, c, "first label"), last = label(l, 1, c, "last label");
        const long step = l.fields.size() > 2 ? label(l, 2, c, "increment") : 1;
        if (last < first) fail(l.at, key(c), "GENERATE: the last label is below the first");
        if (l.fields.size() > 3) fail(l.at, key(c), "GENERATE takes first, last and an increment");
        if ((last - first) / step + 1 > static_cast<long>(defined))
          fail(l.at, key(c), "GENERATE: the range holds more labels than the deck has " + std::string(what) + "s");
        for (long v = first;; v += step) {
          out.push_back(v);
          if (last - v < step) break;  // never step past LONG_MAX
        }
        continue;
      }
      for (const std::string& f : l.fields) {
        if (f.empty()) continue;
        if (const auto v = integer(f)) {
          out.push_back(*v);
          continue;
        }
        const auto it = sets.find(deck_upper(f));
        if (it == sets.end())
          fail(l.at, key(c), "'" + f + "' is neither a " + what + " label nor a " + what + " set defined before");
        out.insert(out.end(), it->second.labels.begin(), it->second.labels.end());
      }
    }
    for (long v : out) {
      const bool there = nodes ? m_.has_node(v) : elements_.count(v) != 0;
      if (!there) fail(c.at, key(c), std::string(what) + " " + std::to_string(v) + " is not defined");
    }
    return out;
  }

  void node_set(const DeckCard& c) {
    only(c, {"NSET", "GENERATE", "ELSET", "UNSORTED", "INTERNAL"});
    std::vector<long> labels;
    if (c.has("ELSET")) {
      const Set& es = element_set_named(c, param(c, "ELSET"));
      std::set<long> seen;
      for (long e : es.labels)
        for (long n : elements_.at(e).nodes)
          if (seen.insert(n).second) labels.push_back(n);
    } else {
      labels = set_members(c, true);
    }
    add_to_set(node_sets_, param(c, "NSET"), labels);
  }

  void element_set(const DeckCard& c) {
    only(c, {"ELSET", "GENERATE", "UNSORTED", "INTERNAL"});
    add_to_set(element_sets_, param(c, "ELSET"), set_members(c, false));
  }

  const Set& element_set_named(const DeckCard& c, const std::string& name) const {
    const auto it = element_sets_.find(deck_upper(name));
    if (it == element_sets_.end()) fail(c.at, key(c), "element set '" + name + "' is not defined before");
    return it->second;
  }
  const Set& node_set_named(const DeckCard& c, const std::string& name) const {
    const auto it = node_sets_.find(deck_upper(name));
    if (it == node_sets_.end()) fail(c.at, key(c), "node set '" + name + "' is not defined before");
    return it->second;
  }
  // A data field that names a node or a node set.
  std::vector<long> node_or_set(const DeckDataLine& l, const DeckCard& c) const {
    const std::string& f = l.fields.front();
    if (const auto v = integer(f)) {
      if (!m_.has_node(*v)) fail(l.at, key(c), "node " + f + " is not defined");
      return {*v};
    }
    const auto it = node_sets_.find(deck_upper(f));
    if (it == node_sets_.end()) fail(l.at, key(c), "'" + f + "' is neither a node label nor a node set defined before");
    return it->second.labels;
  }

  // ---- materials ---------------------------------------------------------------
  void material(const DeckCard& c) {
    only(c, {"NAME"});
    const std::string name = param(c, "NAME");
    auto [it, fresh] = materials_.try_emplace(deck_upper(name));
    if (!fresh)
      fail(c.at, "NAME", "material '" + name + "' is defined twice (line " + std::to_string(it->second.at.line) + ")");
    it->second.name = name;
    it->second.at = c.at;
    material_ = &it->second;
  }
  Material& current_material(const DeckCard& c) {
    if (!material_) fail(c.at, key(c), "*" + c.keyword + " belongs under a *MATERIAL");
    return *material_;
  }
  static void single_line(const DeckCard& c) {
    if (c.data.size() > 1)
      fail(c.data[1].at, key(c), "temperature-dependent data (more than one line) is not supported");
  }
  void elastic(const DeckCard& c) {
    only(c, {"TYPE"});
    if (c.has("TYPE") && deck_upper(c.params.at("TYPE")) != "ISO" && deck_upper(c.params.at("TYPE")) != "ISOTROPIC")
      fail(c.at, "TYPE", "only isotropic elasticity (TYPE=ISO) is supported");
    Material& mat = current_material(c);
    const DeckDataLine& l = first_line(c, "E, nu");
    single_line(c);
    mat.E = number(l, 0, c, "Young's modulus");
    mat.nu = number(l, 1, c, "Poisson's ratio");
  }
  void density(const DeckCard& c) {
    only(c, {});
    Material& mat = current_material(c);
    const DeckDataLine& l = first_line(c, "the density");
    single_line(c);
    mat.rho = number(l, 0, c, "density");
  }
  // The model's material of that deck name, added on first use.
  std::string use_material(const DeckCard& c, const std::string& name) {
    const auto it = materials_.find(deck_upper(name));
    if (it == materials_.end()) fail(c.at, "MATERIAL", "material '" + name + "' is not defined");
    const Material& d = it->second;
    if (!d.E) fail(d.at, "*MATERIAL", "material '" + d.name + "' has no *ELASTIC");
    if (!m_.materials.count(d.name)) {
      fe::Material mat;
      mat.name = d.name;
      mat.E = *d.E;
      mat.nu = *d.nu;
      mat.rho = d.rho.value_or(0.0);
      m_.materials[d.name] = mat;
      where_["material:" + d.name] = d.at;
    }
    return d.name;
  }

  // ---- properties ----------------------------------------------------------------
  // Gives the property to every element of the card's ELSET, which must be
  // of its category and have none yet.
  int assign(const DeckCard& c, Property p) {
    const int index = static_cast<int>(properties_.size());
    const Set& set = element_set_named(c, param(c, "ELSET"));
    if (set.labels.empty()) fail(c.at, "ELSET", "element set '" + set.name + "' is empty");
    for (long id : set.labels) {
      Element& e = elements_.at(id);
      if (e.type->category != p.category)
        fail(c.at, key(c),
             "element " + std::to_string(id) + " (" + e.type->name + ", line " + std::to_string(e.at.line) +
                 ") cannot take a *" + c.keyword);
      if (e.property >= 0)
        fail(c.at, key(c),
             "element " + std::to_string(id) + " already has a property from line " +
                 std::to_string(properties_[static_cast<size_t>(e.property)].at.line));
      e.property = index;
    }
    properties_.push_back(std::move(p));
    return index;
  }

  fe::Vec3 direction_line(const DeckCard& c, size_t k) const {
    if (c.data.size() <= k) return fe::Vec3(0, 0, -1);
    const DeckDataLine& l = c.data[k];
    const fe::Vec3 n(number(l, 0, c, "n1 x"), number_or(l, 1, c, "n1 y", 0.0), number_or(l, 2, c, "n1 z", 0.0));
    if (n.norm() == 0.0) fail(l.at, key(c), "the 1-direction n1 is the zero vector");
    return n.normalized();
  }

  void beam_section(const DeckCard& c) {
    only(c, {"ELSET", "MATERIAL", "SECTION", "POISSON"});
    fe::BeamSection s;
    s.name = element_set_named(c, param(c, "ELSET")).name;
    s.material = use_material(c, param(c, "MATERIAL"));
    const std::string shape = deck_upper(param(c, "SECTION"));
    const DeckDataLine& l = first_line(c, "the section's dimensions");
    auto equal = [&](double a, double b, const char* what) {
      if (std::abs(a - b) > 1e-12 * std::max(std::abs(a), std::abs(b)))
        fail(l.at, key(c),
             std::string("SECTION=") + shape + ": " + what + " (rigflex's sections are doubly symmetric)");
    };
    if (shape == "RECT") {
      s.shape = fe::SectionShape::Rectangle;
      s.width = number(l, 0, c, "a");
      s.height = number(l, 1, c, "b");
    } else if (shape == "CIRC") {
      // Abaqus gives the radius; CalculiX gives the two diameters of an ellipse.
      s.shape = fe::SectionShape::Circle;
      if (l.fields.size() >= 2 && !l.fields[1].empty()) {
        s.diameter = number(l, 0, c, "diameter in 1-direction");
        equal(s.diameter, number(l, 1, c, "diameter in 2-direction"), "the two diameters differ");
      } else {
        s.diameter = 2.0 * number(l, 0, c, "radius");
      }
    } else if (shape == "PIPE") {
      s.shape = fe::SectionShape::Tube;
      s.diameter = 2.0 * number(l, 0, c, "outer radius");
      s.wall = number(l, 1, c, "wall thickness");
    } else if (shape == "BOX") {
      s.shape = fe::SectionShape::Box;
      s.width = number(l, 0, c, "a");
      s.height = number(l, 1, c, "b");
      s.web_thickness = number(l, 2, c, "t1");
      s.flange_thickness = number(l, 3, c, "t2");
      equal(s.web_thickness, number(l, 4, c, "t3"), "t1 and t3 differ");
      equal(s.flange_thickness, number(l, 5, c, "t4"), "t2 and t4 differ");
      s.wall = s.web_thickness;
    } else if (shape == "I") {
      s.shape = fe::SectionShape::ISection;
      const double offset = number(l, 0, c, "l"), h = number(l, 1, c, "h");
      s.height = h;
      s.width = number(l, 2, c, "b1");
      equal(s.width, number(l, 3, c, "b2"), "the flange widths b1 and b2 differ");
      s.flange_thickness = number(l, 4, c, "t1");
      equal(s.flange_thickness, number(l, 5, c, "t2"), "the flange thicknesses t1 and t2 differ");
      s.web_thickness = number(l, 6, c, "t3");
      equal(offset, 0.5 * h, "l is not h/2 (the reference point is not the centroid)");
    } else {
      fail(c.at, "SECTION", "SECTION=" + shape + " is not supported (RECT, CIRC, PIPE, BOX, I)");
    }
    add_beam_section(c, std::move(s), direction_line(c, 1));
  }

  void beam_general_section(const DeckCard& c) {
    only(c, {"ELSET", "SECTION", "DENSITY", "POISSON"});
    if (c.has("SECTION") && deck_upper(c.params.at("SECTION")) != "GENERAL")
      fail(c.at, "SECTION", "only SECTION=GENERAL is supported with *BEAM GENERAL SECTION");
    if (c.data.size() < 3) fail(c.at, key(c), "three data lines: A, I11, I12, I22, J; n1; E, G");
    const DeckDataLine& l = c.data[0];
    fe::BeamSection s;
    s.name = element_set_named(c, param(c, "ELSET")).name;
    s.shape = fe::SectionShape::General;
    s.A = number(l, 0, c, "A");
    s.Iy = number(l, 1, c, "I11");  // about the 1-axis = rigflex's local y
    if (number(l, 2, c, "I12") != 0.0) fail(l.at, key(c), "I12 must be 0: rigflex's beams bend about principal axes");
    s.Iz = number(l, 3, c, "I22");
    s.J = number(l, 4, c, "J");
    const DeckDataLine& el = c.data[2];
    fe::Material mat;
    mat.name = s.name + " (general section)";
    mat.E = number(el, 0, c, "E");
    const double G = number(el, 1, c, "G");
    if (G <= 0.0) fail(el.at, key(c), "G must be positive");
    mat.nu = mat.E / (2.0 * G) - 1.0;
    mat.rho = 0.0;
    if (c.has("DENSITY")) {
      const DeckDataLine dl{c.at, {c.params.at("DENSITY")}, ""};
      mat.rho = number(dl, 0, c, "DENSITY");
    }
    if (m_.materials.count(mat.name)) fail(c.at, "ELSET", "a second general section for '" + s.name + "'");
    m_.materials[mat.name] = mat;
    where_["material:" + mat.name] = c.at;
    s.material = mat.name;
    general_section_ = add_beam_section(c, std::move(s), direction_line(c, 1));
  }

  int add_beam_section(const DeckCard& c, fe::BeamSection s, const fe::Vec3& n1) {
    if (m_.beam_sections.count(s.name)) fail(c.at, "ELSET", "element set '" + s.name + "' has a beam section already");
    Property p;
    p.category = Category::beam;
    p.at = c.at;
    p.name = s.name;
    p.n1 = n1;
    where_["beam_section:" + s.name] = c.at;
    m_.beam_sections[s.name] = std::move(s);
    return assign(c, std::move(p));
  }

  void transverse_shear(const DeckCard& c) {
    only(c, {});
    if (general_section_ < 0) fail(c.at, key(c), "*TRANSVERSE SHEAR STIFFNESS follows a *BEAM GENERAL SECTION here");
    const Property& p = properties_[static_cast<size_t>(general_section_)];
    fe::BeamSection& s = m_.beam_sections.at(p.name);
    const double G = m_.materials.at(s.material).G();
    const DeckDataLine& l = first_line(c, "K23, K13");
    s.shear_area_z = number(l, 0, c, "K23") / G;  // shear along the 2-direction = local z
    s.shear_area_y = number(l, 1, c, "K13") / G;
  }

  void shell_section(const DeckCard& c) {
    only(c, {"ELSET", "MATERIAL", "OFFSET"});
    if (c.has("OFFSET") && number(DeckDataLine{c.at, {c.params.at("OFFSET")}, ""}, 0, c, "OFFSET") != 0.0)
      fail(c.at, "OFFSET", "shell offsets are not supported (rigflex's shells lie on their mid-surface)");
    fe::ShellSection s;
    s.name = element_set_named(c, param(c, "ELSET")).name;
    s.material = use_material(c, param(c, "MATERIAL"));
    s.thickness = number(first_line(c, "the thickness"), 0, c, "thickness");
    if (m_.shell_sections.count(s.name))
      fail(c.at, "ELSET", "element set '" + s.name + "' has a shell section already");
    Property p;
    p.category = Category::shell;
    p.at = c.at;
    p.name = s.name;
    where_["shell_section:" + s.name] = c.at;
    m_.shell_sections[s.name] = std::move(s);
    assign(c, std::move(p));
  }

  void solid_section(const DeckCard& c) {
    only(c, {"ELSET", "MATERIAL"});
    Property p;
    p.category = Category::solid;
    p.at = c.at;
    p.name = use_material(c, param(c, "MATERIAL"));
    assign(c, std::move(p));
  }

  void mass(const DeckCard& c) {
    only(c, {"ELSET"});
    Property p;
    p.category = Category::mass;
    p.at = c.at;
    p.values = {number(first_line(c, "the mass"), 0, c, "mass")};
    assign(c, std::move(p));
  }

  void rotary_inertia(const DeckCard& c) {
    only(c, {"ELSET"});
    const DeckDataLine& l = first_line(c, "I11, I22, I33, I12, I13, I23");
    Property p;
    p.category = Category::rotary;
    p.at = c.at;
    // Abaqus's products are the tensor's off-diagonal terms (-integral x y dm),
    // as rigflex's are.
    for (size_t k = 0; k < 6; ++k) p.values.push_back(number_or(l, k, c, "inertia", 0.0));
    assign(c, std::move(p));
  }

  void spring(const DeckCard& c) {
    only(c, {"ELSET"});
    const Set& set = element_set_named(c, param(c, "ELSET"));
    if (set.labels.empty()) fail(c.at, "ELSET", "element set '" + set.name + "' is empty");
    const ElementType* type = elements_.at(set.labels.front()).type;
    Property p;
    p.category = Category::spring;
    p.at = c.at;
    if (type->category == Category::spring && std::string(type->name) != "SPRINGA") {
      if (c.data.size() < 2) fail(c.at, key(c), "two data lines: the DOF(s), then the stiffness");
      const DeckDataLine& dofs = c.data[0];
      const long dof1 = label(dofs, 0, c, "DOF");
      const long dof2 = std::string(type->name) == "SPRING2" ? label(dofs, 1, c, "second DOF") : dof1;
      if (dof1 > 6 || dof2 > 6) fail(dofs.at, key(c), "DOFs are within 1..6");
      p.dof1 = static_cast<int>(dof1);
      p.dof2 = static_cast<int>(dof2);
      if (p.dof2 != p.dof1)
        fail(dofs.at, key(c),
             "a spring between different DOFs (" + std::to_string(p.dof1) + ", " + std::to_string(p.dof2) +
                 ") has no rigflex spring");
      p.values = {number(c.data[1], 0, c, "stiffness")};
      if (c.data.size() > 2) fail(c.data[2].at, key(c), "temperature-dependent stiffness is not supported");
    } else {
      // SPRINGA: the stiffness alone (CalculiX) or after an empty first line (Abaqus: "," or blank).
      const bool empty_first = c.data.size() == 2 && std::all_of(c.data[0].fields.begin(), c.data[0].fields.end(),
                                                                 [](const std::string& f) { return f.empty(); });
      p.values = {number(empty_first ? c.data[1] : first_line(c, "the stiffness"), 0, c, "stiffness")};
    }
    for (long id : set.labels)
      if (elements_.at(id).type != type)
        fail(c.at, "ELSET", "element set '" + set.name + "' mixes element types under one *SPRING");
    assign(c, std::move(p));
  }

  // ---- supports and couplings -------------------------------------------------------
  void boundary(const DeckCard& c) {
    only(c, {"OP", "TYPE"});
    if (c.has("TYPE") && deck_upper(c.params.at("TYPE")) != "DISPLACEMENT")
      fail(c.at, "TYPE", "only TYPE=DISPLACEMENT boundary conditions are read");
    for (const DeckDataLine& l : c.data) {
      if (l.fields.size() < 2) fail(l.at, key(c), "node or node set, then the DOFs");
      const std::vector<long> nodes = node_or_set(l, c);
      fe::DofMask fixed{};
      const std::string kind = deck_upper(l.fields[1]);
      auto set = [&](int a, int b) {
        for (int d = a; d <= b; ++d) fixed[static_cast<size_t>(d - 1)] = true;
      };
      if (kind == "ENCASTRE") {
        set(1, 6);
      } else if (kind == "PINNED") {
        set(1, 3);
      } else if (kind == "XSYMM" || kind == "YSYMM" || kind == "ZSYMM") {
        const int axis = kind[0] - 'X' + 1;
        set(axis, axis);
        for (int r = 4; r <= 6; ++r)
          if (r - 3 != axis) set(r, r);
      } else {
        const long first = label(l, 1, c, "first DOF");
        const long last = l.fields.size() > 2 && !l.fields[2].empty() ? label(l, 2, c, "last DOF") : first;
        if (first > 6 || last > 6 || last < first)
          fail(l.at, key(c), "DOFs " + std::to_string(first) + " to " + std::to_string(last) + " are not within 1..6");
        if (number_or(l, 3, c, "prescribed value", 0.0) != 0.0)
          fail(l.at, key(c), "a nonzero prescribed displacement is a load; rigflex holds DOFs at zero only");
        set(static_cast<int>(first), static_cast<int>(last));
      }
      for (long n : nodes) {
        auto& [mask, at] = supports_[n];
        if (at.line == 0) at = l.at;
        for (size_t d = 0; d < 6; ++d) mask[d] = mask[d] || fixed[d];
      }
    }
  }

  void rigid_body(const DeckCard& c) {
    only(c, {"NSET", "ELSET", "REF NODE"});
    const long ref = reference_node(c);
    std::vector<long> nodes;
    if (c.has("NSET") == c.has("ELSET")) fail(c.at, key(c), "give either NSET= or ELSET=");
    if (c.has("NSET")) {
      nodes = node_set_named(c, c.params.at("NSET")).labels;
    } else {
      for (long e : element_set_named(c, c.params.at("ELSET")).labels)
        nodes.insert(nodes.end(), elements_.at(e).nodes.begin(), elements_.at(e).nodes.end());
    }
    fe::RigidCoupling rc;
    rc.id = "rigid body line " + std::to_string(c.at.line);
    rc.reference = ref;
    rc.dependents = distinct_without(nodes, ref);
    if (rc.dependents.empty()) fail(c.at, key(c), "the rigid body has no node besides its reference node");
    where_["coupling:" + rc.id] = c.at;
    m_.couplings.push_back(std::move(rc));
  }

  long reference_node(const DeckCard& c) const {
    const std::string& r = param(c, "REF NODE");
    const auto v = integer(r);
    if (v) {
      if (!m_.has_node(*v)) fail(c.at, "REF NODE", "node " + r + " is not defined");
      return *v;
    }
    const Set& s = node_set_named(c, r);
    if (s.labels.size() != 1) fail(c.at, "REF NODE", "node set '" + r + "' holds more than one node");
    return s.labels.front();
  }

  static std::vector<fe::NodeId> distinct_without(const std::vector<long>& nodes, long ref) {
    std::vector<fe::NodeId> out;
    std::set<long> seen{ref};
    for (long n : nodes)
      if (seen.insert(n).second) out.push_back(n);
    return out;
  }

  // Faces of the solids as Abaqus numbers them (S1..S6, S1..S4): corner
  // positions; the mid-edge nodes of a face follow from the element's edges.
  std::vector<long> face_nodes(const Element& e, const std::string& face, const DeckDataLine& l,
                               const DeckCard& c) const {
    if (e.type->category == Category::shell) return e.nodes;  // SPOS, SNEG: the element's nodes
    static const std::vector<std::vector<int>> hex{{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                                   {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
    static const std::vector<std::vector<int>> tet{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
    if (e.type->category != Category::solid) fail(l.at, key(c), "element faces are read for shells and solids only");
    const bool is_tet = e.type->nodes == 10;
    const auto& faces = is_tet ? tet : hex;
    const auto k = face.size() == 2 && face[0] == 'S' ? integer(face.substr(1)) : std::nullopt;
    if (!k || *k < 1 || *k > static_cast<long>(faces.size()))
      fail(l.at, key(c), "face '" + face + "' is not one of S1..S" + std::to_string(faces.size()));
    const std::vector<int>& corners = faces[static_cast<size_t>(*k - 1)];
    std::vector<long> out;
    for (int i : corners) out.push_back(e.nodes[static_cast<size_t>(i)]);
    static const int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    static const int tet_edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    const int corners_total = is_tet ? 4 : 8;
    for (int m = corners_total; m < e.type->nodes; ++m) {
      const int* edge = is_tet ? tet_edges[m - 4] : hex_edges[m - 8];
      const auto in_face = [&](int v) { return std::find(corners.begin(), corners.end(), v) != corners.end(); };
      if (in_face(edge[0]) && in_face(edge[1])) out.push_back(e.nodes[static_cast<size_t>(m)]);
    }
    return out;
  }

  void surface(const DeckCard& c) {
    only(c, {"NAME", "TYPE"});
    const std::string name = param(c, "NAME");
    const std::string type = c.has("TYPE") ? deck_upper(c.params.at("TYPE")) : "ELEMENT";
    if (type != "NODE" && type != "ELEMENT") fail(c.at, "TYPE", "TYPE=NODE or TYPE=ELEMENT surfaces are read");
    Surface& s = surfaces_[deck_upper(name)];
    if (s.at.line != 0) fail(c.at, "NAME", "surface '" + name + "' is defined twice");
    s.at = c.at;
    for (const DeckDataLine& l : c.data) {
      if (l.fields.empty() || l.fields.front().empty()) fail(l.at, key(c), "a node, set or element expected");
      if (type == "NODE") {
        const double w = number_or(l, 1, c, "weight", 1.0);
        if (!(w > 0.0)) fail(l.at, key(c), "a node's weight must be positive");
        for (long n : node_or_set(l, c)) s.nodes.push_back({n, w});
        continue;
      }
      if (l.fields.size() < 2) fail(l.at, key(c), "element or element set, then the face (S1, S2, ...)");
      std::vector<long> ids;
      if (const auto v = integer(l.fields[0])) {
        if (!elements_.count(*v)) fail(l.at, key(c), "element " + l.fields[0] + " is not defined");
        ids = {*v};
      } else {
        ids = element_set_named(c, l.fields[0]).labels;
      }
      for (long id : ids)
        for (long n : face_nodes(elements_.at(id), deck_upper(l.fields[1]), l, c)) s.nodes.push_back({n, 1.0});
    }
    if (s.nodes.empty()) fail(c.at, key(c), "surface '" + name + "' holds no node");
  }

  void coupling(const DeckCard& c) {
    only(c, {"REF NODE", "SURFACE", "CONSTRAINT NAME"});
    const long ref = reference_node(c);
    const std::string& surface_name = param(c, "SURFACE");
    const auto it = surfaces_.find(deck_upper(surface_name));
    if (it == surfaces_.end()) fail(c.at, "SURFACE", "surface '" + surface_name + "' is not defined before");
    const std::string id =
        c.has("CONSTRAINT NAME") ? c.params.at("CONSTRAINT NAME") : "coupling line " + std::to_string(c.at.line);
    if (i_ + 1 >= cards_.size() || (cards_[i_ + 1].keyword != "KINEMATIC" && cards_[i_ + 1].keyword != "DISTRIBUTING"))
      fail(c.at, key(c), "*COUPLING is followed by *KINEMATIC or *DISTRIBUTING");
    const DeckCard& kind = cards_[++i_];
    fe::DofMask dofs{};
    for (const DeckDataLine& l : kind.data) {
      const long first = label(l, 0, kind, "first DOF");
      const long last = l.fields.size() > 1 && !l.fields[1].empty() ? label(l, 1, kind, "last DOF") : first;
      if (first > 6 || last > 6 || last < first) fail(l.at, key(kind), "DOFs are within 1..6");
      for (long d = first; d <= last; ++d) dofs[static_cast<size_t>(d - 1)] = true;
    }
    if (kind.data.empty()) dofs.fill(true);
    std::vector<long> nodes;
    std::map<long, double> weight;
    for (const auto& [n, w] : it->second.nodes) {
      if (!weight.count(n)) nodes.push_back(n);
      weight[n] = w;
    }
    if (kind.keyword == "KINEMATIC") {
      only(kind, {});
      fe::RigidCoupling rc;
      rc.id = id;
      rc.reference = ref;
      rc.dependents = distinct_without(nodes, ref);
      rc.dofs = dofs;
      where_["coupling:" + id] = c.at;
      m_.couplings.push_back(std::move(rc));
      return;
    }
    only(kind, {"WEIGHTING METHOD"});
    if (kind.has("WEIGHTING METHOD") && deck_upper(kind.params.at("WEIGHTING METHOD")) != "UNIFORM")
      fail(kind.at, "WEIGHTING METHOD", "only UNIFORM weighting is read");
    if (std::find(dofs.begin(), dofs.end(), false) != dofs.end())
      fail(kind.at, key(kind), "a distributing coupling of some DOFs only: rigflex's couples all six");
    fe::DistributingCoupling dc;
    dc.id = id;
    dc.reference = ref;
    for (long n : distinct_without(nodes, ref)) {
      dc.nodes.push_back(n);
      dc.weights.push_back(weight.at(n));
    }
    where_["coupling:" + id] = c.at;
    m_.distributing_couplings.push_back(std::move(dc));
  }

  // ---- the model's elements -----------------------------------------------------------
  void build_elements() {
    std::map<long, size_t> mass_at;  // node -> index in point_masses
    for (const auto& [id, e] : elements_) {
      const std::string name = std::to_string(id);
      if (e.property < 0)
        fail(e.at, "*ELEMENT", "element " + name + " (" + e.type->name + ") has no section or property");
      const Property& p = properties_[static_cast<size_t>(e.property)];
      switch (e.type->category) {
        case Category::beam:
          add_beam(id, e, p);
          break;
        case Category::shell: {
          fe::ShellElement s;
          s.id = name;
          s.nodes.assign(e.nodes.begin(), e.nodes.end());
          s.section = p.name;
          where_["shell:" + name] = e.at;
          m_.shells.push_back(std::move(s));
          break;
        }
        case Category::solid: {
          fe::SolidElement s;
          s.id = name;
          s.nodes.assign(e.nodes.begin(), e.nodes.end());
          s.material = p.name;
          where_["solid:" + name] = e.at;
          m_.solids.push_back(std::move(s));
          break;
        }
        case Category::mass:
        case Category::rotary: {
          const long node = e.nodes.front();
          auto [it, fresh] = mass_at.try_emplace(node, m_.point_masses.size());
          if (fresh) {
            fe::PointMass pm;
            pm.id = name;
            pm.node = node;
            m_.point_masses.push_back(pm);
            where_["point_mass:" + name] = e.at;
          }
          fe::PointMass& pm = m_.point_masses[it->second];
          if (e.type->category == Category::mass) {
            pm.mass += p.values[0];
          } else {
            for (size_t k = 0; k < 6; ++k) pm.inertia[k] += p.values[k];
          }
          break;
        }
        case Category::spring:
          add_spring(name, e, p);
          break;
      }
    }
  }

  void add_beam(long id, const Element& e, const Property& p) {
    const fe::Vec3 a = m_.position(e.nodes.front()), b = m_.position(e.nodes.back());
    const fe::Vec3 t = b - a;
    const fe::Vec3 z = t.cross(p.n1);  // Abaqus's n2 = t x n1 is rigflex's local z
    if (t.norm() == 0.0 || z.norm() < 1e-6 * t.norm())
      fail(e.at, "*ELEMENT",
           "beam " + std::to_string(id) + " lies along its section's 1-direction n1 (line " +
               std::to_string(p.at.line) + "); give n1 at right angles to the member");
    std::vector<std::array<fe::NodeId, 2>> pieces;
    if (e.nodes.size() == 2)
      pieces.push_back({e.nodes[0], e.nodes[1]});
    else
      pieces = {{e.nodes[0], e.nodes[1]}, {e.nodes[1], e.nodes[2]}};
    for (size_t k = 0; k < pieces.size(); ++k) {
      fe::BeamElement be;
      be.id = std::to_string(id) + (pieces.size() > 1 ? "." + std::to_string(k + 1) : "");
      be.nodes = pieces[k];
      be.section = p.name;
      be.orientation = z.normalized();
      where_["beam:" + be.id] = e.at;
      m_.beams.push_back(std::move(be));
    }
  }

  void add_spring(const std::string& name, const Element& e, const Property& p) {
    fe::Spring s;
    s.id = name;
    s.node = e.nodes.front();
    if (e.nodes.size() > 1) s.other = e.nodes.back();
    if (std::string(e.type->name) == "SPRINGA") {
      s.axial = p.values[0];
    } else {
      s.stiffness[static_cast<size_t>(p.dof1 - 1)] = p.values[0];
    }
    where_["spring:" + name] = e.at;
    m_.springs.push_back(std::move(s));
  }

  void build_supports() {
    for (const auto& [node, entry] : supports_) {
      fe::Support s;
      s.id = "boundary of node " + std::to_string(node);
      s.node = node;
      s.fixed = entry.first;
      where_["support:" + s.id] = entry.second;
      m_.supports.push_back(s);
    }
    for (const auto& [upper, set] : node_sets_) {
      std::vector<fe::NodeId> ids;
      std::set<long> seen;
      for (long n : set.labels)
        if (seen.insert(n).second) ids.push_back(n);
      m_.node_sets[set.name] = ids;
    }
  }

  struct Surface {
    DeckWhere at;
    std::vector<std::pair<long, double>> nodes;
  };

  std::vector<DeckCard> cards_;
  std::string source_;
  size_t i_ = 0;
  fe::Model m_;
  std::string name_;
  bool in_step_ = false;
  std::map<long, Element> elements_;
  Sets node_sets_, element_sets_;
  std::map<std::string, Material> materials_;
  Material* material_ = nullptr;
  int general_section_ = -1;
  std::vector<Property> properties_;
  std::map<long, std::pair<fe::DofMask, DeckWhere>> supports_;
  std::map<std::string, Surface> surfaces_;
  std::map<std::string, DeckWhere> where_;  // "kind:id" -> where it was defined
};

}  // namespace

ModelFile parse_abaqus_deck(const std::string& text, const std::string& source) {
  return DeckReader(read_deck_cards(text, source), source).read();
}

}  // namespace rigflex::io
