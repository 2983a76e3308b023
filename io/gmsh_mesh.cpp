#include "io/gmsh_mesh.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <sstream>
#include <type_traits>

#include "fe/node_merger.hpp"
#include "fe/solid_element.hpp"
#include "io/file_text.hpp"
#include "io/input_error.hpp"

namespace rigflex::io {
namespace {

// The file, read line by line (whitespace-separated tokens) in its ASCII
// parts and value by value in a binary file's sections.
class Lines {
 public:
  Lines(const std::string& text, std::string source) : text_(text), source_(std::move(source)) {}
  bool done() const { return pos_ >= text_.size(); }
  int line() const { return line_; }  // 1-based number of the line last taken
  std::vector<std::string> take(const std::string& what) {
    if (done()) fail(what + " expected, the file ends");
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string l = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    if (!l.empty() && l.back() == '\r') l.pop_back();
    std::istringstream in(l);
    std::vector<std::string> tokens;
    std::string t;
    while (in >> t) tokens.push_back(t);
    return tokens;
  }
  // A binary value; binary sections end with a newline before their $End line.
  template <class T>
  T binary(const char* what) {
    if (pos_ + sizeof(T) > text_.size()) fail(std::string(what) + " expected, the file ends");
    T v;
    std::memcpy(&v, text_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  void end_binary() {
    if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
  }
  [[noreturn]] void fail(const std::string& message) const {
    if (binary_) throw InputError(source_, 0, "", message + " (at byte " + std::to_string(pos_) + ")");
    throw InputError(source_, line(), "", message);
  }
  bool is_binary() const { return binary_; }
  void set_binary() { binary_ = true; }
  template <class T>
  T number(const std::string& token, const char* what) const {
    T v{};
    const char* end = token.data() + token.size();
    const auto r = std::from_chars(token.data(), end, v);
    if (r.ec != std::errc() || r.ptr != end) fail(std::string(what) + ": '" + token + "' is not a number");
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v)) fail(std::string(what) + " is not finite");
    }
    return v;
  }
  // A line of exactly `count` tokens (count < 0: at least -count).
  std::vector<std::string> take_n(int count, const std::string& what) {
    std::vector<std::string> t = take(what);
    const bool ok = count >= 0 ? static_cast<int>(t.size()) == count : static_cast<int>(t.size()) >= -count;
    if (!ok)
      fail(what + ": expected " + std::to_string(std::abs(count)) + (count < 0 ? " or more" : "") + " values, found " +
           std::to_string(t.size()));
    return t;
  }
  void expect_end(const std::string& section) {
    const std::vector<std::string> t = take("$End" + section);
    if (t.size() != 1 || t[0] != "$End" + section) fail("$End" + section + " expected");
  }

 private:
  const std::string& text_;
  std::string source_;
  size_t pos_ = 0;
  int line_ = 0;
  bool binary_ = false;
};

void read_format(Lines& in) {
  const std::vector<std::string> t = in.take_n(3, "$MeshFormat: version file-type data-size");
  if (t[0] != "4.1") in.fail("MSH version " + t[0] + ": rigflex reads 4.1 (Gmsh 4: File > Export, or -format msh41)");
  if (t[1] == "1") {
    if (t[2] != "8") in.fail("a binary MSH file with " + t[2] + "-byte sizes: rigflex reads 8");
    in.set_binary();
    if (in.binary<int>("the byte-order check") != 1) in.fail("a binary MSH file of the other byte order");
    in.end_binary();
  } else if (t[1] != "0") {
    in.fail("file type " + t[1] + ": expected 0 (ASCII) or 1 (binary)");
  }
  in.expect_end("MeshFormat");
}

// Nodes per element of each Gmsh type a binary file may hold (ASCII lines
// carry their own count).
int gmsh_nodes_per_element(int type) {
  static const std::map<int, int> nodes{{1, 2},  {2, 3},  {3, 4},   {4, 4},   {5, 8},   {6, 6},   {7, 5},
                                        {8, 3},  {9, 6},  {10, 9},  {11, 10}, {12, 27}, {13, 18}, {14, 14},
                                        {15, 1}, {16, 8}, {17, 20}, {18, 15}, {19, 13}};
  const auto it = nodes.find(type);
  return it != nodes.end() ? it->second : 0;
}

void read_names(Lines& in, GmshMesh& mesh) {
  const long count = in.number<long>(in.take_n(1, "$PhysicalNames: count")[0], "count");
  for (long i = 0; i < count; ++i) {
    const std::vector<std::string> t = in.take_n(-3, "physical name: dim tag \"name\"");
    const int dim = in.number<int>(t[0], "dimension");
    const int tag = in.number<int>(t[1], "physical tag");
    // The name is the rest of the line between quotes (it may hold spaces).
    std::string name;
    for (size_t k = 2; k < t.size(); ++k) name += (k > 2 ? " " : "") + t[k];
    if (name.size() < 2 || name.front() != '"' || name.back() != '"') in.fail("a physical name is quoted");
    mesh.group_names[{dim, tag}] = name.substr(1, name.size() - 2);
  }
  in.expect_end("PhysicalNames");
}

// Gmsh writes a physical tag negative to flip an orientation; the group is
// the same.
int physical_tag(const Lines& in, int tag) {
  if (tag == std::numeric_limits<int>::min()) in.fail("physical tag out of range");
  return std::abs(tag);
}

// Entity (dim, tag) -> its physical tags.
using Entities = std::map<std::pair<int, int>, std::vector<int>>;

Entities read_entities(Lines& in) {
  const std::vector<std::string> c = in.take_n(4, "$Entities: points curves surfaces volumes");
  Entities out;
  for (int dim = 0; dim < 4; ++dim) {
    const long count = in.number<long>(c[static_cast<size_t>(dim)], "entity count");
    // Points: tag x y z n phys...; others: tag 6 bounds n phys... m bounding...
    const size_t first = dim == 0 ? 4 : 7;
    for (long i = 0; i < count; ++i) {
      const std::vector<std::string> t = in.take_n(-static_cast<int>(first + 1), "entity");
      const int tag = in.number<int>(t[0], "entity tag");
      const long n = in.number<long>(t[first], "physical tag count");
      if (n < 0 || first + 1 + static_cast<size_t>(n) > t.size()) in.fail("entity: physical tags cut short");
      std::vector<int> phys;
      for (long k = 0; k < n; ++k)
        phys.push_back(physical_tag(in, in.number<int>(t[first + 1 + static_cast<size_t>(k)], "physical tag")));
      out[{dim, tag}] = phys;
    }
  }
  in.expect_end("Entities");
  return out;
}

void read_nodes(Lines& in, GmshMesh& mesh) {
  const std::vector<std::string> h = in.take_n(4, "$Nodes: blocks nodes min-tag max-tag");
  const long blocks = in.number<long>(h[0], "block count");
  for (long b = 0; b < blocks; ++b) {
    const std::vector<std::string> t = in.take_n(4, "node block: dim entity parametric count");
    const bool parametric = in.number<int>(t[2], "parametric") != 0;
    const long n = in.number<long>(t[3], "node count");
    std::vector<long> tags;
    for (long k = 0; k < n; ++k) tags.push_back(in.number<long>(in.take_n(1, "node tag")[0], "node tag"));
    for (long k = 0; k < n; ++k) {
      const std::vector<std::string> x = in.take_n(-3, "node coordinates");
      if (!parametric && x.size() != 3) in.fail("node coordinates: expected x y z");
      const fe::Vec3 p(in.number<double>(x[0], "x"), in.number<double>(x[1], "y"), in.number<double>(x[2], "z"));
      if (!mesh.nodes.emplace(tags[static_cast<size_t>(k)], p).second)
        in.fail("node " + std::to_string(tags[static_cast<size_t>(k)]) + " is given twice");
    }
  }
  in.expect_end("Nodes");
}

void read_elements(Lines& in, const Entities& entities, GmshMesh& mesh) {
  const std::vector<std::string> h = in.take_n(4, "$Elements: blocks elements min-tag max-tag");
  const long blocks = in.number<long>(h[0], "block count");
  for (long b = 0; b < blocks; ++b) {
    const std::vector<std::string> t = in.take_n(4, "element block: dim entity type count");
    const int dim = in.number<int>(t[0], "dimension");
    const int entity = in.number<int>(t[1], "entity tag");
    const int type = in.number<int>(t[2], "element type");
    const long n = in.number<long>(t[3], "element count");
    const auto it = entities.find({dim, entity});
    for (long k = 0; k < n; ++k) {
      const std::vector<std::string> e = in.take_n(-2, "element: tag and its nodes");
      GmshElement el;
      el.tag = in.number<long>(e[0], "element tag");
      el.type = type;
      el.dim = dim;
      el.line = in.line();
      if (it != entities.end()) el.physicals = it->second;
      for (size_t j = 1; j < e.size(); ++j) {
        const long node = in.number<long>(e[j], "node tag");
        if (!mesh.nodes.count(node)) in.fail("element " + e[0] + " names node " + e[j] + ", which is not in $Nodes");
        el.nodes.push_back(node);
      }
      mesh.elements.push_back(std::move(el));
    }
  }
  in.expect_end("Elements");
}

// The same sections in a binary file: sizes and tags as 8-byte size_t,
// dimensions, entity and physical tags as 4-byte int, coordinates as double.
Entities read_entities_binary(Lines& in) {
  size_t count[4];
  for (size_t& c : count) c = in.binary<size_t>("entity count");
  Entities out;
  for (int dim = 0; dim < 4; ++dim)
    for (size_t i = 0; i < count[dim]; ++i) {
      const int tag = in.binary<int>("entity tag");
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) in.binary<double>("entity bounds");
      const size_t n = in.binary<size_t>("physical tag count");
      std::vector<int> phys;
      for (size_t k = 0; k < n; ++k) phys.push_back(physical_tag(in, in.binary<int>("physical tag")));
      if (dim > 0) {
        const size_t b = in.binary<size_t>("bounding entity count");
        for (size_t k = 0; k < b; ++k) in.binary<int>("bounding entity");
      }
      out[{dim, tag}] = phys;
    }
  in.end_binary();
  in.expect_end("Entities");
  return out;
}

void read_nodes_binary(Lines& in, GmshMesh& mesh) {
  const size_t blocks = in.binary<size_t>("block count");
  for (int k = 0; k < 3; ++k) in.binary<size_t>("node count and tags");
  for (size_t b = 0; b < blocks; ++b) {
    const int dim = in.binary<int>("dimension");
    in.binary<int>("entity tag");
    const bool parametric = in.binary<int>("parametric") != 0;
    const size_t n = in.binary<size_t>("node count");
    std::vector<size_t> tags;
    for (size_t k = 0; k < n; ++k) tags.push_back(in.binary<size_t>("node tag"));
    for (size_t k = 0; k < n; ++k) {
      fe::Vec3 p;
      for (int d = 0; d < 3; ++d) p(d) = in.binary<double>("node coordinate");
      if (parametric)
        for (int d = 0; d < dim; ++d) in.binary<double>("parametric coordinate");
      if (!p.allFinite()) in.fail("node " + std::to_string(tags[k]) + ": a coordinate is not finite");
      if (!mesh.nodes.emplace(static_cast<long>(tags[k]), p).second)
        in.fail("node " + std::to_string(tags[k]) + " is given twice");
    }
  }
  in.end_binary();
  in.expect_end("Nodes");
}

void read_elements_binary(Lines& in, const Entities& entities, GmshMesh& mesh) {
  const size_t blocks = in.binary<size_t>("block count");
  for (int k = 0; k < 3; ++k) in.binary<size_t>("element count and tags");
  for (size_t b = 0; b < blocks; ++b) {
    const int dim = in.binary<int>("dimension");
    const int entity = in.binary<int>("entity tag");
    const int type = in.binary<int>("element type");
    const size_t n = in.binary<size_t>("element count");
    const int per = gmsh_nodes_per_element(type);
    if (per == 0) in.fail("element type " + std::to_string(type) + ": its node count is not known here");
    const auto it = entities.find({dim, entity});
    for (size_t k = 0; k < n; ++k) {
      GmshElement el;
      el.tag = static_cast<long>(in.binary<size_t>("element tag"));
      el.type = type;
      el.dim = dim;
      if (it != entities.end()) el.physicals = it->second;
      for (int j = 0; j < per; ++j) {
        const auto node = static_cast<long>(in.binary<size_t>("node tag"));
        if (!mesh.nodes.count(node))
          in.fail("element " + std::to_string(el.tag) + " names node " + std::to_string(node) +
                  ", which is not in $Nodes");
        el.nodes.push_back(node);
      }
      mesh.elements.push_back(std::move(el));
    }
  }
  in.end_binary();
  in.expect_end("Elements");
}

// Skips a section rigflex does not use ($Periodic, $NodeData, ...).
void skip(Lines& in, const std::string& section) {
  while (!in.done()) {
    const std::vector<std::string> t = in.take("$End" + section);
    if (t.size() == 1 && t[0] == "$End" + section) return;
  }
  in.fail("$End" + section + " expected, the file ends");
}

}  // namespace

GmshMesh parse_gmsh(const std::string& text, const std::string& source) {
  Lines in(text, source);
  GmshMesh mesh;
  Entities entities;
  bool format = false, nodes = false, elements = false;
  while (!in.done()) {
    const std::vector<std::string> t = in.take("a section");
    if (t.empty()) continue;
    const std::string& s = t[0];
    if (s == "$MeshFormat") {
      read_format(in);
      format = true;
    } else if (!format) {
      in.fail("not a Gmsh mesh: $MeshFormat expected first");
    } else if (s == "$PhysicalNames") {
      read_names(in, mesh);
    } else if (s == "$Entities") {
      entities = in.is_binary() ? read_entities_binary(in) : read_entities(in);
    } else if (s == "$Nodes") {
      in.is_binary() ? read_nodes_binary(in, mesh) : read_nodes(in, mesh);
      nodes = true;
    } else if (s == "$Elements") {
      if (!nodes) in.fail("$Elements before $Nodes");
      in.is_binary() ? read_elements_binary(in, entities, mesh) : read_elements(in, entities, mesh);
      elements = true;
    } else if (in.is_binary() && s.size() > 1 && s[0] == '$') {
      in.fail("section " + s +
              " in a binary file: rigflex reads $MeshFormat, $PhysicalNames, $Entities, $Nodes "
              "and $Elements of a binary file (save without the others, or as ASCII)");
    } else if (s.size() > 1 && s[0] == '$') {
      skip(in, s.substr(1));
    } else {
      in.fail("a section ($Nodes, $Elements, ...) expected, found '" + s + "'");
    }
  }
  if (!format) throw InputError(source, 1, "", "not a Gmsh mesh: empty");
  if (!elements) throw InputError(source, in.line(), "", "the mesh has no $Elements section");
  return mesh;
}

GmshMesh read_gmsh(const std::filesystem::path& file) { return parse_gmsh(read_file_text(file), file.string()); }

std::string gmsh_type_name(int type) {
  static const std::map<int, const char*> names{
      {1, "2-node line"},        {2, "3-node triangle"},      {3, "4-node quadrangle"},
      {4, "4-node tetrahedron"}, {5, "8-node hexahedron"},    {6, "6-node prism"},
      {7, "5-node pyramid"},     {8, "3-node line"},          {9, "6-node triangle"},
      {10, "9-node quadrangle"}, {11, "10-node tetrahedron"}, {12, "27-node hexahedron"},
      {13, "18-node prism"},     {14, "14-node pyramid"},     {15, "point"},
      {16, "8-node quadrangle"}, {17, "20-node hexahedron"},  {18, "15-node prism"},
      {19, "13-node pyramid"}};
  const auto it = names.find(type);
  return it != names.end() ? it->second : "type " + std::to_string(type);
}

int gmsh_group(const GmshMesh& mesh, int dim, const std::string& name) {
  for (const auto& [key, n] : mesh.group_names)
    if (key.first == dim && n == name) return key.second;
  return -1;
}

namespace {

// Gmsh's mid-edge nodes follow its own edge tables (gmsh.info, "Node
// ordering"); rigflex's (= VTK's, fe/solid_element.hpp) differ for hex20 and
// tet10. The position in Gmsh's list of each of rigflex's mid-edge nodes,
// found by the corner pair.
template <size_t N, size_t M>
std::vector<int> mid_edge_order(const std::array<std::array<int, 2>, N>& gmsh_edges,
                                const std::array<std::array<int, 2>, M>& ours, int corners) {
  std::vector<int> order;
  for (int c = 0; c < corners; ++c) order.push_back(c);
  for (const auto& e : ours)
    for (size_t k = 0; k < N; ++k)
      if (std::minmax(gmsh_edges[k][0], gmsh_edges[k][1]) == std::minmax(e[0], e[1]))
        order.push_back(corners + static_cast<int>(k));
  return order;
}

// For each supported Gmsh type: rigflex's node order as positions in Gmsh's.
const std::vector<int>* node_order(int type) {
  static const std::vector<int> quad4{0, 1, 2, 3}, quad8{0, 1, 2, 3, 4, 5, 6, 7}, hex8{0, 1, 2, 3, 4, 5, 6, 7};
  static const std::vector<int> hex20 = mid_edge_order(
      std::array<std::array<int, 2>, 12>{
          {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}}},
      fe::kHexMidEdges, 8);
  static const std::vector<int> tet10 = mid_edge_order(
      std::array<std::array<int, 2>, 6>{{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}}, fe::kTetMidEdges, 4);
  switch (type) {
    case 3:
      return &quad4;
    case 16:
      return &quad8;
    case 5:
      return &hex8;
    case 17:
      return &hex20;
    case 11:
      return &tet10;
    default:
      return nullptr;
  }
}

std::string unsupported(const GmshElement& e) {
  const std::string what = gmsh_type_name(e.type);
  if (e.dim == 2)
    return what +
           ": rigflex's shells are 4- and 8-node quadrangles (Gmsh: Recombine Surface, and "
           "Mesh.SecondOrderIncomplete = 1 for 8 nodes)";
  return what +
         ": rigflex's solids are 8- and 20-node hexahedra and 10-node tetrahedra (Gmsh: "
         "Mesh.ElementOrder = 2 for tetrahedra; Mesh.SecondOrderIncomplete = 1 for 20-node hexahedra)";
}

}  // namespace

void add_gmsh_mesh(fe::Model& model, const GmshMesh& mesh, const GmshPlacement& placement, const std::string& file) {
  // Physical tag -> (shell section | material), per dimension.
  std::map<int, std::string> shell_of, solid_of;
  for (const auto& [group, section] : placement.shells) shell_of[gmsh_group(mesh, 2, group)] = section;
  for (const auto& [group, material] : placement.solids) solid_of[gmsh_group(mesh, 3, group)] = material;
  fe::NodeMerger merger(model);
  std::map<long, fe::NodeId> ids;
  auto node = [&](long tag) {
    auto it = ids.find(tag);
    if (it == ids.end()) it = ids.emplace(tag, merger.at(mesh.nodes.at(tag))).first;
    return it->second;
  };
  std::map<std::pair<int, int>, std::set<fe::NodeId>> group_nodes;
  for (const GmshElement& e : mesh.elements) {
    const std::map<int, std::string>* placed = e.dim == 2 ? &shell_of : e.dim == 3 ? &solid_of : nullptr;
    std::vector<std::string> targets;
    if (placed)
      for (int p : e.physicals)
        if (const auto it = placed->find(p); it != placed->end()) targets.push_back(it->second);
    for (int p : e.physicals)
      for (long n : e.nodes) group_nodes[{e.dim, p}].insert(node(n));
    if (targets.empty()) continue;
    if (targets.size() > 1)
      throw InputError(file, e.line, "", "element " + std::to_string(e.tag) + " lies in two placed physical groups");
    const std::vector<int>* order = node_order(e.type);
    if (!order) throw InputError(file, e.line, "", "element " + std::to_string(e.tag) + " is a " + unsupported(e));
    if (order->size() != e.nodes.size())
      throw InputError(file, e.line, "",
                       "element " + std::to_string(e.tag) + " has " + std::to_string(e.nodes.size()) + " nodes, a " +
                           gmsh_type_name(e.type) + " " + std::to_string(order->size()));
    std::vector<fe::NodeId> nodes;
    for (int k : *order) nodes.push_back(node(e.nodes[static_cast<size_t>(k)]));
    const std::string id = placement.id + "." + std::to_string(e.tag);
    if (e.dim == 2) {
      model.shells.push_back({id, nodes, targets.front(), placement.mass});
    } else {
      model.solids.push_back({id, nodes, targets.front(), placement.mass});
    }
  }
  for (const auto& [key, nodes] : group_nodes) {
    const auto name = mesh.group_names.find(key);
    if (name == mesh.group_names.end()) continue;  // an unnamed group
    if (model.node_sets.count(name->second))
      throw InputError(file, 0, "", "physical group '" + name->second + "': the model has a node set of that name");
    model.node_sets[name->second] = std::vector<fe::NodeId>(nodes.begin(), nodes.end());
  }
}

}  // namespace rigflex::io
