#include "fe/meshers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "fe/error.hpp"
#include "fe/solid_types.hpp"

namespace rigflex::fe {
namespace {

void require_positive_divisions(const std::string& id, const std::string& key, int n) {
  if (n < 1) throw ModelError({"mesher", id, key}, "'" + id + "': " + key + " must be at least 1");
}

Vec3 bilinear(const std::array<Vec3, 4>& c, double s, double t) {
  return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
}

// Distance from p to segment [a, b] and the fraction of the closest point.
std::pair<double, double> project_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double f = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return {(a + f * ab - p).norm(), f};
}

// Meshes members and hangs joint reference nodes from the nearest member.
void mesh_members_with_joints(Model& model, NodeMerger& merger, std::vector<MemberSpec> members,
                              const std::vector<Vec3>& joints, const std::string& owner,
                              const std::string& joint_set) {
  std::vector<std::pair<size_t, double>> attach(joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t m = 0; m < members.size(); ++m) {
      const auto [d, f] = project_on_segment(joints[j], members[m].from, members[m].to);
      if (d < best) {
        best = d;
        attach[j] = {m, f};
      }
    }
    const auto [m, f] = attach[j];
    if (f > 1e-9 && f < 1 - 1e-9) members[m].stations.push_back(f);
  }
  for (const MemberSpec& m : members) mesh_member(model, merger, m);

  std::vector<NodeId> set;
  for (size_t j = 0; j < joints.size(); ++j) {
    const MemberSpec& m = members[attach[j].first];
    const NodeId on_member = merger.at(m.from + attach[j].second * (m.to - m.from));
    const NodeId joint = merger.at(joints[j]);
    if (joint != on_member) {
      const std::string id = owner + ".joint" + std::to_string(j + 1);
      model.couplings.push_back({id, joint, {on_member}, {true, true, true, true, true, true}});
    }
    set.push_back(joint);
  }
  model.node_sets[joint_set] = set;
}

MemberSpec plain_member(std::string id, const Vec3& from, const Vec3& to, int elements, std::string section) {
  MemberSpec m;
  m.id = std::move(id);
  m.from = from;
  m.to = to;
  m.elements = elements;
  m.section = std::move(section);
  return m;
}

}  // namespace

std::vector<NodeId> mesh_member(Model& model, NodeMerger& merger, const MemberSpec& spec) {
  require_positive_divisions(spec.id, "elements", spec.elements);
  if ((spec.to - spec.from).norm() == 0.0)
    throw ModelError({"member", spec.id, "to"}, "member '" + spec.id + "' has zero length");
  std::vector<double> f;
  for (int k = 0; k <= spec.elements; ++k) f.push_back(static_cast<double>(k) / spec.elements);
  for (double s : spec.stations) {
    if (!(s > 0.0 && s < 1.0))
      throw ModelError({"member", spec.id, "stations"}, "member '" + spec.id + "': stations must lie in (0, 1)");
    f.push_back(s);
  }
  std::sort(f.begin(), f.end());
  f.erase(std::unique(f.begin(), f.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), f.end());

  std::vector<NodeId> ids;
  for (double s : f) ids.push_back(merger.at(spec.from + s * (spec.to - spec.from)));
  for (size_t k = 0; k + 1 < ids.size(); ++k) {
    BeamElement b;
    b.id = spec.id + ":" + std::to_string(k + 1);
    b.nodes = {ids[k], ids[k + 1]};
    b.section = spec.section;
    b.orientation = spec.orientation;
    b.theory = spec.theory;
    b.mass = spec.mass;
    b.rotary_inertia = spec.rotary_inertia;
    model.beams.push_back(b);
  }
  return ids;
}

PatchNodes mesh_shell_patch(Model& model, NodeMerger& merger, const PatchSpec& spec) {
  require_positive_divisions(spec.id, "divisions", spec.nx);
  require_positive_divisions(spec.id, "divisions", spec.ny);
  const int order = spec.quadratic ? 2 : 1;
  PatchNodes grid;
  grid.cols = order * spec.nx + 1;
  grid.rows = order * spec.ny + 1;
  grid.ids.assign(static_cast<size_t>(grid.rows * grid.cols), 0);
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.cols; ++c) {
      if (spec.quadratic && r % 2 == 1 && c % 2 == 1) continue;  // no mid-face node in 8-node elements
      const double s = static_cast<double>(c) / (grid.cols - 1), t = static_cast<double>(r) / (grid.rows - 1);
      grid.ids[static_cast<size_t>(r * grid.cols + c)] = merger.at(bilinear(spec.corners, s, t));
    }
  int k = 0;
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i) {
      const int c0 = order * i, r0 = order * j, c1 = c0 + order, r1 = r0 + order;
      ShellElement e;
      e.id = spec.id + ":" + std::to_string(++k);
      e.section = spec.section;
      e.mass = spec.mass;
      e.nodes = {grid.at(r0, c0), grid.at(r0, c1), grid.at(r1, c1), grid.at(r1, c0)};
      if (spec.quadratic) {
        const int cm = c0 + 1, rm = r0 + 1;
        e.nodes.insert(e.nodes.end(), {grid.at(r0, cm), grid.at(rm, c1), grid.at(r1, cm), grid.at(rm, c0)});
      }
      model.shells.push_back(e);
    }
  return grid;
}

namespace {

Vec3 trilinear(const std::array<Vec3, 8>& c, double u, double v, double w) {
  const Vec3 bottom = (1 - v) * ((1 - u) * c[0] + u * c[1]) + v * ((1 - u) * c[3] + u * c[2]);
  const Vec3 top = (1 - v) * ((1 - u) * c[4] + u * c[5]) + v * ((1 - u) * c[7] + u * c[6]);
  return (1 - w) * bottom + w * top;
}

// The Kuhn split of a cell into 6 tetrahedra around its diagonal 1-7, in the
// cell's hex8 corner numbers; every one is positively oriented, and the split
// of each face matches the neighbouring cell's.
constexpr std::array<std::array<int, 4>, 6> kKuhnTets{
    {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}}};

}  // namespace

long mesh_solid_block(Model& model, NodeMerger& merger, const SolidBlockSpec& spec) {
  require_positive_divisions(spec.id, "divisions", spec.nx);
  require_positive_divisions(spec.id, "divisions", spec.ny);
  require_positive_divisions(spec.id, "divisions", spec.nz);
  const SolidType* type = solid_type_named(spec.element);
  if (!type)
    throw ModelError({"solid_block", spec.id, "element"},
                     "solid block '" + spec.id + "': element '" + spec.element + "' is not " + solid_type_names());
  const bool tets = type->nodes == 10, quadratic = type->nodes != 8;
  long count = 0;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        std::array<Vec3, 8> x;
        std::array<NodeId, 8> corner;
        for (int a = 0; a < 8; ++a) {
          const int di = (a == 1 || a == 2 || a == 5 || a == 6), dj = (a == 2 || a == 3 || a == 6 || a == 7),
                    dk = a >= 4;
          x[a] = trilinear(spec.corners, double(i + di) / spec.nx, double(j + dj) / spec.ny, double(k + dk) / spec.nz);
          corner[a] = merger.at(x[a]);
        }
        // Mid-edge nodes at the straight edge's midpoint: shared edges meet
        // the same point from both sides, and edges stay straight.
        auto mid = [&](int a, int b) { return merger.at(0.5 * (x[a] + x[b])); };
        auto add = [&](std::vector<NodeId> nodes) {
          SolidElement e;
          e.id = spec.id + ":" + std::to_string(++count);
          e.nodes = std::move(nodes);
          e.material = spec.material;
          e.mass = spec.mass;
          model.solids.push_back(std::move(e));
        };
        if (!tets) {
          std::vector<NodeId> nodes(corner.begin(), corner.end());
          if (quadratic)
            for (const auto& e : kHexMidEdges) nodes.push_back(mid(e[0], e[1]));
          add(std::move(nodes));
          continue;
        }
        for (const auto& t : kKuhnTets) {
          std::vector<NodeId> nodes;
          for (int a : t) nodes.push_back(corner[a]);
          for (const auto& e : kTetMidEdges) nodes.push_back(mid(t[e[0]], t[e[1]]));
          add(std::move(nodes));
        }
      }
  return count;
}

BoxGirderNodes mesh_box_girder(Model& model, NodeMerger& merger, const BoxGirderSpec& spec) {
  const std::string& id = spec.id;
  const Vec3 axis = spec.to - spec.from;
  if (axis.norm() == 0.0) throw ModelError({"box_girder", id, "to"}, "box girder '" + id + "' has zero length");
  for (auto [v, key] : {std::pair{spec.width, "width"}, {spec.height, "height"},
                        {spec.web_thickness, "web_thickness"}, {spec.flange_thickness, "flange_thickness"}})
    if (!(v > 0.0)) throw ModelError({"box_girder", id, key}, "box girder '" + id + "': " + key + " must be positive");
  if (2 * spec.web_thickness >= spec.width || 2 * spec.flange_thickness >= spec.height)
    throw ModelError({"box_girder", id, "web_thickness"}, "box girder '" + id + "': walls thicker than the section");
  const Vec3 ex = axis.normalized();
  const Vec3 up_perp = spec.up - spec.up.dot(ex) * ex;
  if (up_perp.norm() < 1e-9)
    throw ModelError({"box_girder", id, "up"}, "box girder '" + id + "': up is parallel to the axis");
  const Vec3 ez = up_perp.normalized(), ey = ez.cross(ex);
  const double hy = 0.5 * (spec.width - spec.web_thickness), hz = 0.5 * (spec.height - spec.flange_thickness);
  auto P = [&](double x, double y, double z) -> Vec3 { return spec.from + x * ex + y * ey + z * ez; };
  const double L = axis.norm();

  model.shell_sections[id + ".web"] = {id + ".web", spec.material, spec.web_thickness};
  model.shell_sections[id + ".flange"] = {id + ".flange", spec.material, spec.flange_thickness};
  auto patch = [&](const std::string& name, std::array<Vec3, 4> c, int nx, int ny, const std::string& sec) {
    return mesh_shell_patch(model, merger, {id + "." + name, c, nx, ny, spec.quadratic, sec, spec.mass});
  };
  std::vector<PatchNodes> sides;
  sides.push_back(patch("top", {P(0, -hy, hz), P(L, -hy, hz), P(L, hy, hz), P(0, hy, hz)}, spec.n_along,
                        spec.n_width, id + ".flange"));
  sides.push_back(patch("bottom", {P(0, -hy, -hz), P(L, -hy, -hz), P(L, hy, -hz), P(0, hy, -hz)}, spec.n_along,
                        spec.n_width, id + ".flange"));
  sides.push_back(patch("web_left", {P(0, hy, -hz), P(L, hy, -hz), P(L, hy, hz), P(0, hy, hz)}, spec.n_along,
                        spec.n_height, id + ".web"));
  sides.push_back(patch("web_right", {P(0, -hy, -hz), P(L, -hy, -hz), P(L, -hy, hz), P(0, -hy, hz)}, spec.n_along,
                        spec.n_height, id + ".web"));
  if (spec.end_plates) {
    for (double x : {0.0, L})
      patch(x == 0.0 ? "end_start" : "end_end", {P(x, -hy, -hz), P(x, hy, -hz), P(x, hy, hz), P(x, -hy, hz)},
            spec.n_width, spec.n_height, id + ".web");
  }
  BoxGirderNodes out;
  if (!spec.end_couplings) return out;
  for (bool start : {true, false}) {
    std::set<NodeId> ring;
    for (const PatchNodes& g : sides) {
      const int c = start ? 0 : g.cols - 1;
      for (int r = 0; r < g.rows; ++r)
        if (g.at(r, c) != 0) ring.insert(g.at(r, c));
    }
    const Vec3 centre = start ? spec.from : spec.to;
    const NodeId ref = merger.at(centre);
    ring.erase(ref);
    model.couplings.push_back({id + (start ? ".start" : ".end"), ref, {ring.begin(), ring.end()},
                               {true, true, true, true, true, true}});
    (start ? out.start_reference : out.end_reference) = ref;
  }
  return out;
}

void build_fixed_frame(Model& model, const FixedFrameSpec& spec) {
  const size_t n = spec.column_bases.size();
  if (n < 2) throw ModelError({"fixed_frame", spec.id, "column_bases"}, "a fixed frame needs at least 2 columns");
  if (!(spec.height > 0.0)) throw ModelError({"fixed_frame", spec.id, "height"}, "fixed frame height must be positive");
  NodeMerger merger(model);
  std::vector<Vec3> tops;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 base = spec.column_bases[i], top = base + spec.height * Vec3::UnitZ();
    tops.push_back(top);
    mesh_member(model, merger,
                plain_member(spec.id + ".column" + std::to_string(i + 1), base, top, spec.elements_per_member,
                             spec.column_section));
    model.supports.push_back({spec.id + ".base" + std::to_string(i + 1), merger.at(base), {true, true, true, true, true, true}});
  }
  std::vector<MemberSpec> beams;
  auto add_beam = [&](size_t a, size_t b) {
    if (a >= n || b >= n || a == b)
      throw ModelError({"fixed_frame", spec.id, "extra_beams"}, "fixed frame beam between invalid columns");
    beams.push_back(plain_member(spec.id + ".beam" + std::to_string(beams.size() + 1), tops[a], tops[b],
                                 spec.elements_per_member, spec.beam_section));
  };
  if (spec.ring)
    for (size_t i = 0; i < n; ++i)
      if (n > 2 || i == 0) add_beam(i, (i + 1) % n);
  for (const auto& [a, b] : spec.extra_beams) add_beam(static_cast<size_t>(a), static_cast<size_t>(b));
  if (beams.empty()) throw ModelError({"fixed_frame", spec.id, "extra_beams"}, "fixed frame has no cross beams");
  mesh_members_with_joints(model, merger, beams, spec.joints, spec.id, spec.joint_set);
}

void build_carrying_frame(Model& model, const CarryingFrameSpec& spec) {
  require_positive_divisions(spec.id, "bays", spec.bays_x);
  require_positive_divisions(spec.id, "bays", spec.bays_y);
  const double z = spec.corner_min.z();
  const double x0 = spec.corner_min.x(), x1 = spec.corner_max.x(), y0 = spec.corner_min.y(), y1 = spec.corner_max.y();
  if (!(x1 > x0 && y1 > y0))
    throw ModelError({"carrying_frame", spec.id, "corner_max"}, "carrying frame corner_max must exceed corner_min in x and y");
  NodeMerger merger(model);
  std::vector<MemberSpec> members;
  auto X = [&](int i) { return x0 + (x1 - x0) * i / spec.bays_x; };
  auto Y = [&](int j) { return y0 + (y1 - y0) * j / spec.bays_y; };
  for (int j = 0; j <= spec.bays_y; ++j)
    for (int i = 0; i < spec.bays_x; ++i)
      members.push_back(plain_member(spec.id + ".x" + std::to_string(j) + "_" + std::to_string(i), Vec3(X(i), Y(j), z),
                                     Vec3(X(i + 1), Y(j), z), spec.elements_per_member, spec.section));
  for (int i = 0; i <= spec.bays_x; ++i)
    for (int j = 0; j < spec.bays_y; ++j)
      members.push_back(plain_member(spec.id + ".y" + std::to_string(i) + "_" + std::to_string(j), Vec3(X(i), Y(j), z),
                                     Vec3(X(i), Y(j + 1), z), spec.elements_per_member, spec.section));
  mesh_members_with_joints(model, merger, members, spec.joints, spec.id, spec.joint_set);
}

}  // namespace rigflex::fe
