#pragma once
// Beam cross-sections. Local axes: x along the member, y and z in the section
// plane; "width" runs along local y, "height" along local z.
#include <optional>
#include <string>

namespace rigflex::fe {

enum class SectionShape { Rectangle, Circle, Box, Tube, ISection, General };

struct BeamSection {
  std::string name;
  std::string material;  // material name
  SectionShape shape = SectionShape::General;
  // Shape dimensions [m]; which ones apply depends on the shape.
  double width = 0.0;             // Rectangle, Box, ISection (flange width): along y
  double height = 0.0;            // Rectangle, Box, ISection (total height): along z
  double diameter = 0.0;          // Circle, Tube (outer)
  double wall = 0.0;              // Tube, Box: wall thickness
  double web_thickness = 0.0;     // ISection (and Box, if its webs differ from wall)
  double flange_thickness = 0.0;  // ISection (and Box, if its flanges differ from wall)
  // General sections: properties given directly.
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0;
  std::optional<double> shear_area_y, shear_area_z;  // absent: shear-rigid in that direction

  void validate() const;  // throws ModelError naming the key
};

// Properties used by the beam element. Iy = integral z^2 dA (bending about y),
// Iz = integral y^2 dA. A shear area of zero means shear-rigid (Euler-Bernoulli).
struct SectionProperties {
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0;
  double shear_area_y = 0.0, shear_area_z = 0.0;
  double Ip() const { return Iy + Iz; }  // polar moment, for torsional inertia
};

// Cowper's shear coefficients depend on Poisson's ratio, so properties are
// computed for a given material.
SectionProperties section_properties(const BeamSection& s, double nu);

}  // namespace rigflex::fe
