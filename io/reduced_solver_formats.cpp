#include "io/reduced_solver_formats.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

namespace rigflex::io {
namespace {

// A reduced coordinate as the other solvers name it: (node or scalar point id, component).
std::vector<std::pair<long, int>> coordinates(const reduction::ReducedFrame& r, int modal_component) {
  std::vector<std::pair<long, int>> out;
  for (const auto& d : r.interface_dofs) out.push_back({d.node, d.local + 1});
  const long base = modal_coordinate_base(r);
  for (int k = 0; k < r.mode_count; ++k) out.push_back({base + k, modal_component});
  return out;
}

std::string field16(const std::string& s) {
  std::string f = s.substr(0, 16);
  f.resize(16, ' ');
  return f;
}

// 10 significant digits in 16 characters, with Nastran's double-precision exponent.
std::string real16(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%16.9E", v);
  std::string s(buf);
  std::replace(s.begin(), s.end(), 'E', 'D');
  return field16(s);
}

void dmig_matrix(std::string& out, const std::string& name, const Eigen::MatrixXd& A,
                 const std::vector<std::pair<long, int>>& at) {
  char head[96];
  std::snprintf(head, sizeof head, "%-8s%-8s%-8s%-8s%-8s%-8s\n", "DMIG", name.c_str(), "0", "6", "2", "0");
  out += head;
  const auto n = static_cast<Eigen::Index>(at.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    std::string card = "DMIG*   " + field16(name) + field16(std::to_string(at[static_cast<size_t>(j)].first)) +
                       field16(std::to_string(at[static_cast<size_t>(j)].second)) + field16("") + "\n";
    bool any = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (at[static_cast<size_t>(i)] > at[static_cast<size_t>(j)] || A(i, j) == 0.0) continue;
      card += "*       " + field16(std::to_string(at[static_cast<size_t>(i)].first)) +
              field16(std::to_string(at[static_cast<size_t>(i)].second)) + real16(A(i, j)) + field16("") + "\n";
      any = true;
    }
    if (any) out += card;
  }
}

std::string abaqus_matrix(const Eigen::MatrixXd& A, const std::vector<std::pair<long, int>>& at) {
  std::string out;
  char line[128];
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j <= i; ++j) {
      if (A(i, j) == 0.0) continue;
      const auto& r = at[static_cast<size_t>(i)];
      const auto& c = at[static_cast<size_t>(j)];
      std::snprintf(line, sizeof line, "%ld, %d, %ld, %d, %.17g\n", r.first, r.second, c.first, c.second, A(i, j));
      out += line;
    }
  return out;
}

}  // namespace

long modal_coordinate_base(const reduction::ReducedFrame& r) {
  long largest = 0;
  for (const auto& n : r.interface_nodes) largest = std::max(largest, static_cast<long>(n.id));
  long base = 1000;
  while (base <= largest) base *= 10;
  return base;
}

std::string nastran_dmig(const reduction::ReducedFrame& r) {
  const auto at = coordinates(r, 0);
  std::string out = "$ Reduced frame '" + r.name + "' written by rigflex (" + to_string(r.method) + ", " +
                    to_string(r.support) + "): " + std::to_string(r.interface_dof_count()) + " interface DOFs on " +
                    "grids with rigflex's node ids";
  out += r.mode_count > 0 ? ", " + std::to_string(r.mode_count) + " modal coordinates on SPOINTs " +
                                std::to_string(modal_coordinate_base(r)) + ".." +
                                std::to_string(modal_coordinate_base(r) + r.mode_count - 1) + "\n"
                          : "\n";
  out += "$ Case control: K2GG = KAAX, M2GG = MAAX, B2GG = BAAX. Units as the model's (SI: N, m, kg, s).\n";
  for (const auto& n : r.interface_nodes) {
    char c[160];
    std::snprintf(c, sizeof c, "$ interface grid %ld at %.10g %.10g %.10g\n", static_cast<long>(n.id), n.position.x(),
                  n.position.y(), n.position.z());
    out += c;
  }
  if (r.mode_count > 0) {
    const long base = modal_coordinate_base(r);
    out += "SPOINT  " + field16(std::to_string(base)).substr(0, 8) + "THRU    " +
           field16(std::to_string(base + r.mode_count - 1)).substr(0, 8) + "\n";
  }
  dmig_matrix(out, "KAAX", r.K, at);
  dmig_matrix(out, "MAAX", r.M, at);
  if (r.C.size() > 0) dmig_matrix(out, "BAAX", r.C, at);
  return out;
}

std::map<std::string, std::string> abaqus_matrix_files(const reduction::ReducedFrame& r, const std::string& stem) {
  const auto at = coordinates(r, 1);
  std::map<std::string, std::string> files;
  std::string inp = "** Reduced frame '" + r.name + "' written by rigflex (" + std::string(to_string(r.method)) + ", " +
                    to_string(r.support) + ") as Abaqus matrices: the interface DOFs on the nodes with rigflex's ids";
  inp += r.mode_count > 0
             ? ", the modal coordinates as DOF 1 of nodes " + std::to_string(modal_coordinate_base(r)) + ".." +
                   std::to_string(modal_coordinate_base(r) + r.mode_count - 1) + " (defined below)\n"
             : "\n";
  inp += "** Include it in the model that holds the interface nodes. Units as the model's.\n";
  if (r.mode_count > 0) {
    inp += "*NODE\n";
    fe::Vec3 c = fe::Vec3::Zero();
    for (const auto& n : r.interface_nodes) c += n.position / static_cast<double>(r.interface_nodes.size());
    char line[128];
    for (int k = 0; k < r.mode_count; ++k) {
      std::snprintf(line, sizeof line, "%ld, %.10g, %.10g, %.10g\n", modal_coordinate_base(r) + k, c.x(), c.y(), c.z());
      inp += line;
    }
  }
  const std::string& name = stem;
  inp += "*MATRIX INPUT, NAME=" + name + "-K, INPUT=" + stem + "_K.txt\n";
  inp += "*MATRIX INPUT, NAME=" + name + "-M, INPUT=" + stem + "_M.txt\n";
  files[stem + "_K.txt"] = abaqus_matrix(r.K, at);
  files[stem + "_M.txt"] = abaqus_matrix(r.M, at);
  std::string assemble = "*MATRIX ASSEMBLE, STIFFNESS=" + name + "-K, MASS=" + name + "-M";
  if (r.C.size() > 0) {
    inp += "*MATRIX INPUT, NAME=" + name + "-C, INPUT=" + stem + "_C.txt\n";
    files[stem + "_C.txt"] = abaqus_matrix(r.C, at);
    assemble += ", VISCOUS DAMPING=" + name + "-C";
  }
  inp += assemble + "\n";
  files[stem + ".inp"] = inp;
  return files;
}

}  // namespace rigflex::io
