// read_reduced_frame (declared in reduced_export.hpp): reduced.json and its
// Matrix Market files back into a ReducedFrame.
#include <algorithm>
#include <climits>
#include <set>

#include "fe/dof.hpp"
#include "io/json_fields.hpp"
#include "io/matrix_market.hpp"
#include "io/reduced_export.hpp"
#include "io/reduced_layout.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;
namespace layout = reduced_layout;
using reduction::ReducedFrame;

class FrameReader {
 public:
  explicit FrameReader(const fs::path& dir)
      : dir_(dir), f_(JsonFields::from_file((dir / layout::kJsonFile).string())) {}

  ReducedFrame read() {
    const JsonNode root = f_.root();
    // Format and version first: a newer file may well have keys this reader does not know.
    read_format(root);
    f_.expect_object(root, {"format", "version", "name", "method", "units", "support", "reference_node",
                            "retained_dofs", "interface_set", "interface_nodes", "dof_order", "mode_count",
                            "mode_frequencies_hz", "coordinate_count", "full_free_dofs", "damping", "state_space",
                            "checks", "files"});
    const JsonNode units = f_.required(root, "units");
    if (*units.value != nlohmann::json(layout::units_json()))
      f_.fail(units, "rigflex reads SI units only: expected " + layout::units_json().dump());
    ReducedFrame r;
    r.name = f_.text(root, "name");
    r.method = choice(f_.required(root, "method"), reduction::parse_reduction_method, "guyan, craig-bampton");
    r.support = choice(f_.required(root, "support"), reduction::parse_frame_support, "grounded, free, reference-node");
    const JsonNode reference = f_.required(root, "reference_node");
    const bool needs_reference = r.support == reduction::FrameSupport::reference_node;
    if (needs_reference && reference.value->is_null())
      f_.fail(reference, "support 'reference-node' needs the reference node's id");
    if (!needs_reference && !reference.value->is_null())
      f_.fail(reference, std::string("must be null with support '") + to_string(r.support) + "'");
    if (needs_reference) r.reference_node = f_.integer(reference);
    r.retained = choice(f_.required(root, "retained_dofs"), reduction::parse_interface_dofs, "translations, all");
    r.interface_set = f_.text(root, "interface_set");
    read_interface(root, r);

    const JsonNode mode_count = f_.required(root, "mode_count");
    r.mode_count = small_integer(mode_count);
    if (r.mode_count < 0) f_.fail(mode_count, "must not be negative");
    r.mode_frequencies_hz = numbers(f_.required(root, "mode_frequencies_hz"), static_cast<size_t>(r.mode_count));
    const Eigen::Index m = r.interface_dof_count();
    const Eigen::Index n = m + r.mode_count;
    const JsonNode coordinates = f_.required(root, "coordinate_count");
    if (f_.integer(coordinates) != n)
      f_.fail(coordinates, "expected " + std::to_string(n) + ": " + std::to_string(m) + " interface DOFs (dof_order) + " +
                               std::to_string(r.mode_count) + " modes (mode_count)");
    const JsonNode full = f_.required(root, "full_free_dofs");
    r.full_free_dofs = f_.integer(full);
    if (r.full_free_dofs < 0) f_.fail(full, "must not be negative");
    r.damping = damping(f_.required(root, "damping"));
    read_state_space(f_.required(root, "state_space"), n, m, r);
    r.checks = checks(f_.required(root, "checks"));
    read_matrices(f_.required(root, "files"), r, n, m);
    return r;
  }

 private:
  void read_format(const JsonNode& root) {
    if (!root.value->is_object()) f_.fail(root, std::string("expected an object, found ") + root.value->type_name());
    const JsonNode format = f_.required(root, "format");
    if (f_.text(format) != kReducedFrameFormat)
      f_.fail(format, std::string("expected '") + kReducedFrameFormat + "'");
    const JsonNode version = f_.required(root, "version");
    version_ = f_.integer(version);
    if (version_ < 1 || version_ > kReducedFrameVersion)
      f_.fail(version, "version " + version.value->dump() + " is not read by this rigflex (it reads versions 1 to " +
                           std::to_string(kReducedFrameVersion) + ")");
  }

  template <class Enum>
  Enum choice(const JsonNode& n, std::optional<Enum> (*parse)(const std::string&), const char* allowed) const {
    const auto v = parse(f_.text(n));
    if (!v) f_.fail(n, "'" + f_.text(n) + "' is not one of: " + allowed);
    return *v;
  }

  int small_integer(const JsonNode& n) const {
    const long v = f_.integer(n);
    if (v < INT_MIN || v > INT_MAX) f_.fail(n, "integer too large");
    return static_cast<int>(v);
  }

  Eigen::VectorXd numbers(const JsonNode& n) const { return to_vector(f_.elements(n)); }
  Eigen::VectorXd numbers(const JsonNode& n, size_t count) const { return to_vector(f_.elements(n, count)); }
  Eigen::VectorXd to_vector(const std::vector<JsonNode>& items) const {
    Eigen::VectorXd v(static_cast<Eigen::Index>(items.size()));
    for (size_t i = 0; i < items.size(); ++i) v(static_cast<Eigen::Index>(i)) = f_.number(items[i]);
    return v;
  }

  fe::Vec3 vec3(const JsonNode& n) const {
    const Eigen::VectorXd v = numbers(n, 3);
    return {v(0), v(1), v(2)};
  }

  reduction::InterfaceDof dof(const JsonNode& n) const {
    f_.expect_object(n, {"node", "dof"});
    reduction::InterfaceDof d;
    d.node = f_.integer(n, "node");
    const JsonNode name = f_.required(n, "dof");
    const std::string text = f_.text(name);
    const std::optional<int> local = fe::dof_index(text);
    if (!local) f_.fail(name, "'" + text + "' is not one of: UX, UY, UZ, RX, RY, RZ");
    d.local = *local;
    return d;
  }

  void read_interface(const JsonNode& root, ReducedFrame& r) const {
    std::set<fe::NodeId> ids;
    for (const JsonNode& e : f_.elements(f_.required(root, "interface_nodes"))) {
      f_.expect_object(e, {"id", "position"});
      const JsonNode id = f_.required(e, "id");
      reduction::InterfaceNode node;
      node.id = f_.integer(id);
      if (!ids.insert(node.id).second) f_.fail(id, "interface node " + std::to_string(node.id) + " listed twice");
      node.position = vec3(f_.required(e, "position"));
      r.interface_nodes.push_back(node);
    }
    std::set<std::pair<fe::NodeId, int>> seen;
    const JsonNode order = f_.required(root, "dof_order");
    for (const JsonNode& e : f_.elements(order)) {
      const reduction::InterfaceDof d = dof(e);
      if (!ids.count(d.node)) f_.fail(f_.required(e, "node"), "node " + std::to_string(d.node) + " is not in interface_nodes");
      if (!seen.insert({d.node, d.local}).second) f_.fail(e, "this DOF is listed twice");
      r.interface_dofs.push_back(d);
    }
    // Each node keeps some of its DOFs (those chosen, less those a support held).
    const int per_node = r.retained == reduction::InterfaceDofs::translations ? 3 : 6;
    std::set<fe::NodeId> kept;
    for (const reduction::InterfaceDof& d : r.interface_dofs) {
      if (d.local >= per_node)
        f_.fail(order, "DOF " + std::string(fe::dof_name(d.local)) + " of node " + std::to_string(d.node) +
                           " with retained_dofs '" + to_string(r.retained) + "'");
      kept.insert(d.node);
    }
    if (kept.size() != ids.size()) f_.fail(order, "an interface node keeps no DOF");
  }

  reduction::RayleighDamping damping(const JsonNode& n) const {
    f_.expect_object(n, {"type", "modes", "zeta", "omega", "alpha", "beta"});
    const JsonNode type = f_.required(n, "type");
    if (f_.text(type) != "rayleigh") f_.fail(type, "expected 'rayleigh'");
    reduction::RayleighDamping d;
    const auto modes = f_.elements(f_.required(n, "modes"), 2);
    const Eigen::VectorXd zeta = numbers(f_.required(n, "zeta"), 2);
    const Eigen::VectorXd omega = numbers(f_.required(n, "omega"), 2);
    for (size_t k = 0; k < 2; ++k) {
      d.modes[k] = small_integer(modes[k]);
      d.zeta[k] = zeta(static_cast<Eigen::Index>(k));
      d.omega[k] = omega(static_cast<Eigen::Index>(k));
    }
    d.alpha = f_.number(n, "alpha");
    d.beta = f_.number(n, "beta");
    return d;
  }

  // Sizes, and the coordinates of the state (version 1: always physical).
  void read_state_space(const JsonNode& n, Eigen::Index coordinates, Eigen::Index interface_dofs,
                        ReducedFrame& r) const {
    if (version_ == 1) {
      f_.expect_object(n, {"states", "inputs", "outputs"});
    } else {
      f_.expect_object(n, {"states", "inputs", "outputs", "coordinates", "rigid_body_modes"});
      auto& ss = r.state_space;
      ss.coordinates = choice(f_.required(n, "coordinates"), reduction::parse_state_coordinates, "physical, modal");
      const JsonNode rigid = f_.required(n, "rigid_body_modes");
      ss.rigid_body_modes = small_integer(rigid);
      const bool modal = ss.coordinates == reduction::StateCoordinates::modal;
      if (ss.rigid_body_modes < 0 || ss.rigid_body_modes > coordinates)
        f_.fail(rigid, "expected 0 to " + std::to_string(coordinates) + " (the reduced coordinates)");
      if (!modal && ss.rigid_body_modes != 0) f_.fail(rigid, "must be 0 with physical coordinates");
    }
    const std::pair<const char*, Eigen::Index> sizes[] = {
        {"states", 2 * coordinates}, {"inputs", interface_dofs}, {"outputs", 2 * interface_dofs}};
    for (const auto& [key, expected] : sizes) {
      const JsonNode v = f_.required(n, key);
      if (f_.integer(v) != expected)
        f_.fail(v, "expected " + std::to_string(expected) + " for " + std::to_string(interface_dofs) +
                       " interface DOFs and " + std::to_string(coordinates) + " reduced coordinates");
    }
  }

  fe::MassProperties mass_properties(const JsonNode& n) const {
    f_.expect_object(n, {"mass", "cog", "inertia"});
    fe::MassProperties p;
    p.mass = f_.number(n, "mass");
    p.cog = vec3(f_.required(n, "cog"));
    const Eigen::VectorXd J = numbers(f_.required(n, "inertia"), 6);  // Jxx Jyy Jzz Jxy Jxz Jyz
    p.inertia << J(0), J(3), J(4), J(3), J(1), J(5), J(4), J(5), J(2);
    return p;
  }

  reduction::ReductionChecks checks(const JsonNode& n) const {
    f_.expect_object(n, {"frequencies", "mac", "rigid_body_modes", "mass_properties", "static_flexibility",
                         "reduced_frequencies_hz", "damping_ratios"});
    reduction::ReductionChecks c;
    for (const JsonNode& e : f_.elements(f_.required(n, "frequencies"))) {
      f_.expect_object(e, {"mode", "full_hz", "reduced_hz", "error_percent", "mac", "matched_mode", "matched_mac"});
      reduction::FrequencyCheck fc;
      fc.mode = small_integer(f_.required(e, "mode"));
      fc.full_hz = f_.number(e, "full_hz");
      fc.reduced_hz = f_.number(e, "reduced_hz");
      fc.error_percent = f_.number(e, "error_percent");
      fc.mac = f_.number(e, "mac");
      fc.matched_mode = small_integer(f_.required(e, "matched_mode"));
      fc.matched_mac = f_.number(e, "matched_mac");
      c.frequencies.push_back(fc);
    }
    const auto rows = f_.elements(f_.required(n, "mac"));
    const size_t cols = rows.empty() ? 0 : f_.elements(rows[0]).size();
    c.mac.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols));
    for (size_t i = 0; i < rows.size(); ++i) c.mac.row(static_cast<Eigen::Index>(i)) = numbers(rows[i], cols).transpose();

    const JsonNode rigid = f_.required(n, "rigid_body_modes");
    f_.expect_object(rigid, {"full", "reduced", "residual"});
    c.rigid_body_modes_full = small_integer(f_.required(rigid, "full"));
    c.rigid_body_modes_reduced = small_integer(f_.required(rigid, "reduced"));
    c.rigid_body_residual = f_.number(rigid, "residual");

    const JsonNode mass = f_.required(n, "mass_properties");
    f_.expect_object(mass, {"comparable", "full", "reduced"});
    c.mass_comparable = f_.boolean(mass, "comparable");
    c.mass_full = mass_properties(f_.required(mass, "full"));
    c.mass_reduced = mass_properties(f_.required(mass, "reduced"));

    const JsonNode flexibility = f_.required(n, "static_flexibility");
    f_.expect_object(flexibility, {"error", "support"});
    c.static_flexibility_error = f_.number(flexibility, "error");
    for (const JsonNode& e : f_.elements(f_.required(flexibility, "support"))) c.static_support.push_back(dof(e));

    c.reduced_frequencies_hz = numbers(f_.required(n, "reduced_frequencies_hz"));
    c.damping_ratios = numbers(f_.required(n, "damping_ratios"), static_cast<size_t>(c.reduced_frequencies_hz.size()));
    return c;
  }

  // A file name from "files": a plain name, so that the export cannot point
  // outside its folder.
  std::string file_name(const JsonNode& files, const char* key) const {
    const JsonNode n = f_.required(files, key);
    const std::string name = f_.text(n);
    if (name.empty() || name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos)
      f_.fail(n, "'" + name + "' is not a plain file name in the folder of reduced.json");
    return name;
  }

  void read_matrices(const JsonNode& files, ReducedFrame& r, Eigen::Index n, Eigen::Index m) const {
    const bool has_t = version_ > 1;
    if (has_t)
      f_.expect_object(files, {"K", "M", "C", "ss_A", "ss_B", "ss_C", "ss_D", "ss_T", layout::kMatKey});
    else
      f_.expect_object(files, {"K", "M", "C", "ss_A", "ss_B", "ss_C", "ss_D", layout::kMatKey});
    file_name(files, layout::kMatKey);
    const std::string origin = std::to_string(m) + " interface DOFs + " + std::to_string(n - m) + " modes in " +
                               layout::kJsonFile;
    if (!has_t) r.state_space.T = Eigen::MatrixXd::Identity(n, n);
    for (const auto& mf : layout::kMatrixFiles) {
      if (!has_t && std::string_view(mf.key) == "ss_T") continue;
      const auto size = layout::matrix_size(mf.key, n, m);
      layout::matrix(r, mf.key) = read_matrix_market(dir_ / file_name(files, mf.key), MatrixShape{size.rows, size.cols, origin});
    }
  }

  fs::path dir_;
  JsonFields f_;
  long version_ = kReducedFrameVersion;
};

}  // namespace

ReducedFrame read_reduced_frame(const fs::path& dir) { return FrameReader(dir).read(); }

}  // namespace rigflex::io
