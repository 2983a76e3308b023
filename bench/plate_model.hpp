#pragma once
// The clamped steel plate of the benchmarks, their --sizes syntax and the
// memory probes they share.
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fe/meshers.hpp"
#include "fe/model.hpp"
#include "fe/node_merger.hpp"
#include "fe/shell_centres.hpp"

namespace rigflex::bench {

// n x n MITC4 elements over 1 m x 1 m x 10 mm, all edges clamped; interior
// nodes carry 6 DOFs: 6 (n-1)^2. quadratic: 8-node elements instead, each
// with its centre's three coordinates as a model file gives them (centres)
// or with the centre condensed statically.
inline int divisions_for(long dofs) { return static_cast<int>(std::lround(std::sqrt(dofs / 6.0))) + 1; }

inline fe::Model clamped_plate(int n, bool quadratic = false, bool centres = true) {
  fe::Model m;
  m.materials["steel"] = {"steel", 2.1e11, 0.3, 7850.0};
  m.shell_sections["plate"] = {"plate", "steel", 0.010};
  fe::NodeMerger merger(m);
  fe::PatchSpec p;
  p.id = "plate";
  p.corners = {fe::Vec3(0, 0, 0), fe::Vec3(1, 0, 0), fe::Vec3(1, 1, 0), fe::Vec3(0, 1, 0)};
  p.nx = p.ny = n;
  p.quadratic = quadratic;
  p.section = "plate";
  const fe::PatchNodes g = fe::mesh_shell_patch(m, merger, p);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c)
      if ((r == 0 || c == 0 || r == g.rows - 1 || c == g.cols - 1) && g.at(r, c) != 0)  // 0: no node there
        m.supports.push_back({"edge", g.at(r, c), {true, true, true, true, true, true}});
  if (quadratic && centres) fe::add_shell_centres(m);
  return m;
}

// "10k,100k,1M" -> 10000, 100000, 1000000 (k and M suffixes, either case).
inline long parse_size(std::string s) {
  double scale = 1;
  if (!s.empty() && (s.back() == 'k' || s.back() == 'K')) scale = 1e3, s.pop_back();
  else if (!s.empty() && (s.back() == 'm' || s.back() == 'M')) scale = 1e6, s.pop_back();
  return std::lround(std::stod(s) * scale);
}
inline std::vector<long> parse_sizes(const std::string& list) {
  std::vector<long> sizes;
  std::istringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) sizes.push_back(parse_size(item));
  return sizes;
}

// A /proc/self/status field in kB (VmRSS, VmHWM), 0 if absent.
inline long status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
  return 0;
}

// Resets VmHWM to the current RSS (Linux >= 4.0); false if not permitted.
inline bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.close();
  return static_cast<bool>(out);
}

inline std::string loadavg() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace rigflex::bench
