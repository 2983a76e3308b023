#include "fe/section.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fe/error.hpp"

namespace rigflex::fe {
namespace {

using std::numbers::pi;

// Saint-Venant torsion constant of a solid a x b rectangle (a >= b) from the
// exact series; the truncated 0.21 formula is 0.15% off for a square.
double rectangle_torsion(double a, double b) {
  if (a < b) std::swap(a, b);
  double sum = 0.0;
  for (int n = 1; n < 200; n += 2) sum += std::tanh(n * pi * a / (2.0 * b)) / std::pow(n, 5);
  return a * b * b * b / 3.0 * (1.0 - 192.0 / std::pow(pi, 5) * (b / a) * sum);
}

}  // namespace

void BeamSection::validate() const {
  auto fail = [&](const std::string& key, const std::string& why) {
    throw ModelError({"beam_section", name, key}, "beam section '" + name + "': " + why);
  };
  auto positive = [&](double v, const char* key) {
    if (!(std::isfinite(v) && v > 0.0)) fail(key, std::string(key) + " must be positive");
  };
  switch (shape) {
    case SectionShape::Rectangle:
      positive(width, "width");
      positive(height, "height");
      break;
    case SectionShape::Circle:
      positive(diameter, "diameter");
      break;
    case SectionShape::Tube:
      positive(diameter, "diameter");
      positive(wall, "wall");
      if (2.0 * wall >= diameter) fail("wall", "wall must be less than half the diameter");
      break;
    case SectionShape::Box: {
      positive(width, "width");
      positive(height, "height");
      const double tw = web_thickness > 0 ? web_thickness : wall;
      const double tf = flange_thickness > 0 ? flange_thickness : wall;
      positive(tw, "wall");
      positive(tf, "wall");
      if (2.0 * tw >= width) fail("wall", "webs must be thinner than half the width");
      if (2.0 * tf >= height) fail("wall", "flanges must be thinner than half the height");
      break;
    }
    case SectionShape::ISection:
      positive(width, "width");
      positive(height, "height");
      positive(web_thickness, "web_thickness");
      positive(flange_thickness, "flange_thickness");
      if (web_thickness >= width) fail("web_thickness", "web must be thinner than the flange width");
      if (2.0 * flange_thickness >= height) fail("flange_thickness", "flanges must be thinner than half the height");
      break;
    case SectionShape::General:
      positive(A, "A");
      positive(Iy, "Iy");
      positive(Iz, "Iz");
      positive(J, "J");
      if (shear_area_y) positive(*shear_area_y, "shear_area_y");
      if (shear_area_z) positive(*shear_area_z, "shear_area_z");
      break;
  }
}

SectionProperties section_properties(const BeamSection& s, double nu) {
  SectionProperties p;
  switch (s.shape) {
    case SectionShape::Rectangle: {
      const double b = s.width, h = s.height;
      p.A = b * h;
      p.Iy = b * h * h * h / 12.0;
      p.Iz = h * b * b * b / 12.0;
      p.J = rectangle_torsion(b, h);
      const double k = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);  // Cowper
      p.shear_area_y = p.shear_area_z = k * p.A;
      break;
    }
    case SectionShape::Circle: {
      const double r = 0.5 * s.diameter;
      p.A = pi * r * r;
      p.Iy = p.Iz = pi * std::pow(r, 4) / 4.0;
      p.J = 2.0 * p.Iy;
      const double k = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);  // Cowper
      p.shear_area_y = p.shear_area_z = k * p.A;
      break;
    }
    case SectionShape::Tube: {
      const double ro = 0.5 * s.diameter, ri = ro - s.wall;
      p.A = pi * (ro * ro - ri * ri);
      p.Iy = p.Iz = pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
      p.J = 2.0 * p.Iy;
      const double m = ri / ro, m2 = (1 + m * m) * (1 + m * m);
      const double k = 6.0 * (1.0 + nu) * m2 / ((7.0 + 6.0 * nu) * m2 + (20.0 + 12.0 * nu) * m * m);  // Cowper
      p.shear_area_y = p.shear_area_z = k * p.A;
      break;
    }
    case SectionShape::Box: {
      const double b = s.width, h = s.height;
      const double tw = s.web_thickness > 0 ? s.web_thickness : s.wall;      // webs: vertical walls
      const double tf = s.flange_thickness > 0 ? s.flange_thickness : s.wall;  // flanges: horizontal walls
      const double bi = b - 2.0 * tw, hi = h - 2.0 * tf;
      p.A = b * h - bi * hi;
      p.Iy = (b * h * h * h - bi * hi * hi * hi) / 12.0;
      p.Iz = (h * b * b * b - hi * bi * bi * bi) / 12.0;
      // Bredt-Batho on the wall mid-line.
      const double bm = b - tw, hm = h - tf;
      p.J = 2.0 * tw * tf * bm * bm * hm * hm / (bm * tw + hm * tf);
      // Shear is carried by the walls parallel to the load.
      p.shear_area_z = 2.0 * h * tw;
      p.shear_area_y = 2.0 * b * tf;
      break;
    }
    case SectionShape::ISection: {
      const double b = s.width, h = s.height, tw = s.web_thickness, tf = s.flange_thickness;
      const double hw = h - 2.0 * tf;
      p.A = 2.0 * b * tf + hw * tw;
      p.Iy = (b * h * h * h - (b - tw) * hw * hw * hw) / 12.0;
      p.Iz = (2.0 * tf * b * b * b + hw * tw * tw * tw) / 12.0;
      // Open thin-walled section: sum of b t^3 / 3 over the plates.
      p.J = (2.0 * b * tf * tf * tf + (h - tf) * tw * tw * tw) / 3.0;
      p.shear_area_z = h * tw;                      // web
      p.shear_area_y = 5.0 / 6.0 * 2.0 * b * tf;  // flanges
      break;
    }
    case SectionShape::General:
      p.A = s.A;
      p.Iy = s.Iy;
      p.Iz = s.Iz;
      p.J = s.J;
      p.shear_area_y = s.shear_area_y.value_or(0.0);
      p.shear_area_z = s.shear_area_z.value_or(0.0);
      break;
  }
  return p;
}

}  // namespace rigflex::fe
