#pragma once
// One measurement record: what the sensors of the rig recorded during one
// free swing (the data contract of shared/spec/rig-conventions.md), and
// where it came from. The simulation makes records (rig/simulation), the
// measurement CSV reader reads them (io/measurement_csv), identification,
// compare and diagnose take them. It lives here, apart from the simulator,
// because rig is the lowest folder that produces one; identify/ needs this
// header and not the integrators.
//
// A record the rig cannot have produced is a RecordError naming the sample
// and the channel; the provenance turns the sample into the file's line
// (RecordProvenance::line_of), so that the command line reports file:line
// without keeping its own table of where each record was read
// (io::record_input_error).
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rigflex::rig {

// Ordered "key: value" pairs: a file's leading comments, or how a simulated
// record was made (the push, the initial condition).
using RecordComments = std::vector<std::pair<std::string, std::string>>;

struct RecordProvenance {
  std::string file;           // the file read ("" when simulated)
  int first_sample_line = 0;  // 1-based line of sample 0 in `file`; 0 when not read from a file
  RecordComments comments;    // in file order; written back in that order
  // What the reader found doubtful but not wrong ("line 120: F1 sits at its
  // maximum ... (clipped?)"): for the command line to show, never fatal.
  std::vector<std::string> warnings;

  // The 1-based line of `sample` (0-based) in `file`; 0 when the record was
  // not read from a file or the sample is unknown (< 0). The reader refuses
  // blank lines among the samples, so sample k is on line first_sample_line + k.
  int line_of(long sample) const;
};

struct Record {
  Eigen::VectorXd t;                   // s, strictly increasing
  Eigen::MatrixXd force, alpha, beta;  // samples x rods: F (N, tension positive), encoder angles (rad)
  // Nominal sample rate: the sensors' rate for a simulated record; for a
  // file its "sample_rate_hz" comment, else from the time stamps. Kept for
  // the record's users; the measurement file carries it only as its comment.
  double sample_rate_hz = 0;
  RecordProvenance provenance;

  int rods() const;     // columns of force
  int samples() const;  // rows of t
  // The value of the first comment with this key; "" if there is none.
  std::string comment(const std::string& key) const;
};

// The nominal rate of samples at times `t` with the given comments: a
// positive, finite "sample_rate_hz" comment, else (samples - 1) over the
// time spanned, else 0 (fewer than two samples).
double nominal_sample_rate(const Eigen::VectorXd& t, const RecordComments& comments);

// A record that does not fit the rig: which sample (0-based, -1 for the
// whole record) and which channel ("alpha2", "F1"; empty when not one).
// Thrown by identification, compare and diagnose; the history index is set
// by whoever took a list of records, so that the record can be found again.
class RecordError : public std::invalid_argument {
 public:
  RecordError(long sample, std::string channel, const std::string& message)
      : std::invalid_argument(message), sample_(sample), channel_(std::move(channel)) {}
  long sample() const { return sample_; }
  const std::string& channel() const { return channel_; }
  int history() const { return history_; }  // index in the list of records taken, -1 unknown
  void set_history(int h) { history_ = h; }

 private:
  long sample_;
  int history_ = -1;
  std::string channel_;
};

}  // namespace rigflex::rig
