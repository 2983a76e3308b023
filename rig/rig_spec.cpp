#include "rig/rig_spec.hpp"

#include "fe/assembly_size.hpp"
#include "fe/error.hpp"
#include "rig/effects.hpp"

namespace rigflex::rig {
namespace {

std::string compose(const SpecSource& w, const std::string& reason) {
  std::string s = w.file;
  if (w.line > 0) s.append(":").append(std::to_string(w.line));
  s.append(": ");
  if (!w.key.empty()) s.append("key '").append(w.key).append("': ");
  return s.append(reason);
}

// What a frame too large for the memory is told.
constexpr const char* kTooLarge =
    " (the machine's memory): mesh the frame coarser, or reduce it on its own (rigflex reduce) and give the rig "
    "its reduced matrices";

reduction::ReducedFrame reduced_frame(const FrameSource& s, const FrameResolveOptions& options) {
  if (s.reduced) return *s.reduced;
  reduction::FrameReductionOptions o = s.reduction;
  o.progress = options.progress;
  o.max_factor_bytes = options.max_bytes;
  o.analyzed = options.analyzed;
  o.assembly_progress = options.assembly_progress;
  if (options.max_bytes > 0) {
    const std::string refusal = fe::assembly_refusal(fe::assembly_size(s.model), options.max_bytes);
    if (!refusal.empty()) throw SpecError(s.model_key, refusal + kTooLarge);
  }
  try {
    reduction::ReducedFrame f = reduction::reduce_frame(s.model, o);
    f.name = s.model_name;
    return f;
  } catch (const fe::ModelError& x) {
    throw SpecError(s.model_key, x.what());
  } catch (const reduction::ReductionError& x) {
    throw SpecError(s.model_key, x.what() + std::string(x.over_memory_limit ? kTooLarge : ""));
  } catch (const std::invalid_argument& x) {
    throw SpecError(s.effect, x.what());
  }
}

std::shared_ptr<const Effect> resolved(const FrameSource& s, const RigGeometry& g, const FrameResolveOptions& options) {
  const reduction::ReducedFrame f = reduced_frame(s, options);
  try {
    if (s.fixed) return std::make_shared<FixedFrameFlexibility>(fixed_frame_model(f, g, s.matching));
    return std::make_shared<CarryingFrameFlexibility>(carrying_frame_model(f, g, s.matching));
  } catch (const std::invalid_argument& x) {
    throw SpecError(s.effect, x.what());
  }
}

}  // namespace

SpecError::SpecError(SpecSource where, const std::string& reason)
    : std::invalid_argument(compose(where, reason)), where_(std::move(where)), reason_(reason) {}

const char* PendingFrame::name() const {
  return source_.fixed ? "fixed_frame_flexibility" : "carrying_frame_flexibility";
}

void PendingFrame::build(RigAssembly&) const {
  throw std::logic_error(std::string(name()) + ": the frame was read but not reduced (rig::resolve_frames)");
}

int RigSpec::pending_frames() const {
  int n = 0;
  for (const auto& e : rig.effects) n += dynamic_cast<const PendingFrame*>(e.get()) != nullptr;
  return n;
}

RigModel resolve_frames(const RigSpec& spec, const std::function<void(const std::string&)>& progress) {
  FrameResolveOptions o;
  o.progress = progress;
  return resolve_frames(spec, o);
}

RigModel resolve_frames(const RigSpec& spec, const FrameResolveOptions& options) {
  RigModel model = spec.rig;
  std::optional<SpecSource> last;  // of the frames resolved, the last one
  for (auto& e : model.effects) {
    if (const auto* p = dynamic_cast<const PendingFrame*>(e.get())) {
      last = p->source().effect;
      e = resolved(p->source(), model.geometry, options);
    }
  }
  if (!last) return model;
  try {
    model.validate();
  } catch (const std::invalid_argument& x) {
    // "field: reason", as the rig reader reports validation: the field is the
    // key, the frame's effect the line (the rest was validated on reading).
    const std::string msg = x.what();
    const auto colon = msg.find(':');
    SpecSource at = *last;
    if (colon != std::string::npos) at.key = msg.substr(0, colon);
    throw SpecError(at, colon == std::string::npos ? msg : msg.substr(colon + 2));
  }
  return model;
}

}  // namespace rigflex::rig
