#pragma once
// What a rig file says, before anything is meshed or reduced. Reading a rig
// file (io/rig_reader.hpp) is pure: a flexible frame given by a frame model
// stays a PendingFrame effect holding the model and the reduction asked for,
// and a frame given by a `rigflex reduce` export holds the export as read.
// resolve_frames is the separate step that reduces each frame and places it
// on the rig's joints; the commands call it, with progress, after reading.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "fe/model.hpp"
#include "reduction/frame_reduction.hpp"
#include "rig/effect.hpp"
#include "rig/frame_models.hpp"
#include "rig/rig_model.hpp"

namespace rigflex::rig {

// Where a value of a rig file came from, so that a step after reading can
// still name the file, line and key of what it could not use.
struct SpecSource {
  std::string file;
  int line = 0;  // 1-based; 0 unknown
  std::string key;
};

// A value of a rig file that turned out unusable after reading. what() reads
// as io::InputError's: "file:line: key 'k': reason".
class SpecError : public std::invalid_argument {
 public:
  SpecError(SpecSource where, const std::string& reason);
  const SpecSource& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  SpecSource where_;
  std::string reason_;
};

// A flexible frame as the rig file gives it.
struct FrameSource {
  bool fixed = true;                               // fixed frame (grounded) or carrying frame (free)
  std::optional<reduction::ReducedFrame> reduced;  // a `rigflex reduce` export, read; else ...
  fe::Model model;                                 // ... a frame model,
  std::string model_name;
  reduction::FrameReductionOptions reduction;      // reduced this way
  FrameMatching matching;
  SpecSource effect;     // the effect's key: errors placing the frame on the joints
  SpecSource model_key;  // its `model` key: errors reducing the frame model
};

// Stands in the rig's effects, in the file's order, for a frame until
// resolve_frames replaces it; a rig still holding one cannot be assembled.
class PendingFrame : public Effect {
 public:
  explicit PendingFrame(FrameSource source) : source_(std::move(source)) {}
  const char* name() const override;  // fixed_frame_flexibility or carrying_frame_flexibility
  void validate(int) const override {}
  void build(RigAssembly&) const override;  // std::logic_error: resolve the frames first
  const FrameSource& source() const { return source_; }

 private:
  FrameSource source_;
};

struct RigSpec {
  RigModel rig;  // complete but for its PendingFrame effects
  int pending_frames() const;
};

// How the frames are reduced: what the user hears, and the memory each
// frame's assembly and factorizations may take.
struct FrameResolveOptions {
  std::function<void(const std::string&)> progress;  // the reduction's stages
  // A frame whose assembly or any factorization would pass max_bytes (0: no
  // limit; estimated before the work) is a SpecError at its model's key.
  double max_bytes = 0;
  std::function<void(const linalg::FactorStatistics&)> analyzed;  // each factorization's analysis
  std::function<void(long done, long total)> assembly_progress;
};

// The rig with every pending frame reduced and placed on the joints. Throws
// SpecError naming the rig file's key when a frame model cannot be reduced
// (or would pass the memory limit) or its interface does not meet the
// joints, or when the resolved rig fails RigModel::validate.
RigModel resolve_frames(const RigSpec& spec, const FrameResolveOptions& options);
RigModel resolve_frames(const RigSpec& spec, const std::function<void(const std::string&)>& progress = {});

}  // namespace rigflex::rig
