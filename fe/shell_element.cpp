// Geometry checks for the flat shell elements (the element matrices are in
// shell_mitc4.cpp and shell_quad8.cpp).
#include "fe/shell_element.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "fe/error.hpp"
#include "fe/shell_common.hpp"
#include "fe/shell_types.hpp"

namespace rigflex::fe {
namespace {

using namespace shell_detail;

// Both elements are formed flat on the mean plane, with rigid offsets to the
// actual nodes. That keeps rigid-body motions exact for any warp, but the
// membrane-bending coupling of a genuinely twisted surface is lost, and the
// offsets stiffen the twist; both effects grow with the warp ratio. Up to 1 %
// of the element size they stay below the discretization error of practical
// meshes; beyond it the mesh should follow the surface more closely. The
// limit applies to the 8-node element as well: it is flat too, so a curved
// (mid-side nodes off the corner plane) element would be flattened silently.
constexpr double kMaxWarp = 1e-2;

// Relative tolerances: nodes closer than this fraction of the element size
// coincide; a Jacobian below this fraction of its mean value counts as zero.
constexpr double kCoincident = 1e-8;
constexpr double kZeroJacobian = 1e-8;

[[noreturn]] void fail(const std::string& element_id, const std::string& why) {
  throw ModelError({"shell", element_id, "nodes"}, "shell '" + element_id + "': " + why);
}

void check_coincident(const std::vector<Vec3>& x, const std::string& id) {
  double size = 0.0;
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = i + 1; j < x.size(); ++j) size = std::max(size, (x[i] - x[j]).norm());
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = i + 1; j < x.size(); ++j)
      if (!((x[i] - x[j]).norm() > kCoincident * size))
        fail(id, "nodes " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " coincide");
}

// The Jacobian is checked at the integration points (2x2, and 3x3 for the
// 8-node element) and at the nodes: a concave or bow-tie quadrilateral can
// keep positive values at the Gauss points while folding over at a corner.
// There is no "clockwise" error in 3D: the normal follows the node order.
void check_jacobian(const LocalFrame& f, const std::string& id) {
  const bool quadratic = f.xy.rows() == 8;
  const ShapeFn shape = quadratic ? shape_q8 : shape_q4;
  const double mean_det = f.area / 4.0;  // the reference square has area 4
  auto check_at = [&](double xi, double eta, const std::string& where) {
    const double det = jacobian(shape(xi, eta), f.xy).determinant();
    if (!(det > kZeroJacobian * mean_det)) {
      std::ostringstream msg;
      msg << "zero or negative Jacobian at " << where
          << " (degenerate, concave or self-intersecting element, or nodes not in the order "
             "corners counter-clockwise then mid-sides 1-2, 2-3, 3-4, 4-1)";
      fail(id, msg.str());
    }
  };
  for (int rule : quadratic ? std::vector<int>{2, 3} : std::vector<int>{2})
    for (const GaussPoint& g : gauss_rule(rule)) check_at(g.xi, g.eta, "an integration point");
  for (int i = 0; i < static_cast<int>(f.xy.rows()); ++i) {
    const Vector2d r = node_reference_coords(i);
    check_at(r.x(), r.y(), "node " + std::to_string(i + 1));
  }
}

}  // namespace

void check_shell_geometry(const std::vector<Vec3>& x, const std::string& element_id) {
  if (!shell_type_with_nodes(x.size()))
    fail(element_id, "needs " + shell_node_counts() + " nodes, has " + std::to_string(x.size()));
  for (const Vec3& p : x)
    if (!p.allFinite()) fail(element_id, "non-finite node coordinate");
  check_coincident(x, element_id);
  const Vec3 normal = (x[2] - x[0]).cross(x[3] - x[1]);
  if (!(normal.norm() > 0.0)) fail(element_id, "zero area (diagonals parallel)");
  const LocalFrame f = make_local_frame(x);
  if (f.max_warp() > kMaxWarp) {
    std::ostringstream msg;
    msg << "warped: nodes lie up to " << f.max_warp() * 100.0 << " % of the element size off the mean plane (limit "
        << kMaxWarp * 100.0 << " %); refine the mesh on curved or twisted surfaces";
    fail(element_id, msg.str());
  }
  check_jacobian(f, element_id);
}

}  // namespace rigflex::fe
