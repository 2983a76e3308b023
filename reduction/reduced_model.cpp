#include "reduction/reduced_model.hpp"

namespace rigflex::reduction {

const char* to_string(ReductionMethod m) { return m == ReductionMethod::guyan ? "guyan" : "craig-bampton"; }

const char* to_string(FrameSupport s) {
  switch (s) {
    case FrameSupport::grounded: return "grounded";
    case FrameSupport::free: return "free";
    case FrameSupport::reference_node: return "reference-node";
  }
  return "grounded";
}

const char* to_string(InterfaceDofs d) { return d == InterfaceDofs::translations ? "translations" : "all"; }

std::optional<ReductionMethod> parse_reduction_method(const std::string& s) {
  if (s == "guyan") return ReductionMethod::guyan;
  if (s == "craig-bampton") return ReductionMethod::craig_bampton;
  return std::nullopt;
}

std::optional<FrameSupport> parse_frame_support(const std::string& s) {
  if (s == "grounded") return FrameSupport::grounded;
  if (s == "free") return FrameSupport::free;
  if (s == "reference-node") return FrameSupport::reference_node;
  return std::nullopt;
}

std::optional<InterfaceDofs> parse_interface_dofs(const std::string& s) {
  if (s == "translations") return InterfaceDofs::translations;
  if (s == "all") return InterfaceDofs::all;
  return std::nullopt;
}

const char* to_string(StateCoordinates c) { return c == StateCoordinates::physical ? "physical" : "modal"; }

std::optional<StateCoordinates> parse_state_coordinates(const std::string& s) {
  if (s == "physical") return StateCoordinates::physical;
  if (s == "modal") return StateCoordinates::modal;
  return std::nullopt;
}

}  // namespace rigflex::reduction
