#include "io/measurement_csv.hpp"

namespace rigflex::io {

InputError record_input_error(const std::vector<rig::Record>& records, const rig::RecordError& e) {
  if (e.history() < 0 || static_cast<size_t>(e.history()) >= records.size() ||
      records[static_cast<size_t>(e.history())].provenance.file.empty()) {
    return InputError("(a measurement)", 0, e.channel(), e.what());
  }
  const rig::RecordProvenance& p = records[static_cast<size_t>(e.history())].provenance;
  return InputError(p.file, p.line_of(e.sample()), e.channel(), e.what());
}

}  // namespace rigflex::io
