#pragma once
// Gmsh meshes (MSH 4.1, ASCII or binary), as Gmsh writes them: nodes,
// elements and the physical groups their entities belong to. Read with a parser of our
// own rather than the Gmsh SDK: the format is a few plain sections, the
// SDK (libgmsh, with OpenCASCADE and FLTK) is a heavy dependency for that,
// and a reader of its own can name the file and line of every fault
// (docs/model-exchange.md).
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fe/model.hpp"

namespace rigflex::io {

struct GmshElement {
  long tag = 0;
  int type = 0;                // Gmsh's element type number (3: 4-node quadrangle, 17: 20-node hexahedron, ...)
  int dim = 0;                 // of its entity
  std::vector<long> nodes;     // node tags in Gmsh's order
  std::vector<int> physicals;  // the physical tags of its entity
  int line = 0;                // in the file
};

struct GmshMesh {
  std::map<long, fe::Vec3> nodes;                          // by tag
  std::vector<GmshElement> elements;                       // in file order
  std::map<std::pair<int, int>, std::string> group_names;  // (dim, physical tag) -> name
};

// Throws InputError naming the file and line (in a binary file's sections,
// the byte): another version than 4.1, a section cut short, a number that
// does not read, a node given twice, an element naming a node that is not
// there, a binary file of the other byte order.
GmshMesh parse_gmsh(const std::string& text, const std::string& source);
GmshMesh read_gmsh(const std::filesystem::path& file);

// "20-node hexahedron" for 17, "type 99" for types without a name here.
std::string gmsh_type_name(int type);

// Which physical groups become which elements.
struct GmshPlacement {
  std::string id;                             // element ids are "<id>.<Gmsh element tag>"
  std::map<std::string, std::string> shells;  // surface group -> shell section
  std::map<std::string, std::string> solids;  // volume group -> material
  fe::MassKind mass = fe::MassKind::Consistent;
};

// The physical group's tag of that name and dimension, or -1.
int gmsh_group(const GmshMesh& mesh, int dim, const std::string& name);

// Adds the elements of the placed groups to `model` (4- and 8-node
// quadrangles as shells; 8-, 20-node hexahedra and 10-node tetrahedra as
// solids, reordered to rigflex's node order), their nodes merged with the
// model's by position (1e-6 m), and every physical group's nodes as a node
// set of the group's name. The groups must exist (gmsh_group). Throws
// InputError naming `file` and the element's line for an element type
// rigflex has no element for, or an element in two placed groups, and for
// a node set name the model already has.
void add_gmsh_mesh(fe::Model& model, const GmshMesh& mesh, const GmshPlacement& placement, const std::string& file);

}  // namespace rigflex::io
