#include "io/reduced_mat.hpp"

#include <matio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/reduced_export.hpp"

namespace rigflex::io {
namespace {

namespace fs = std::filesystem;

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct VarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using MatFile = std::unique_ptr<mat_t, MatCloser>;
using MatVar = std::unique_ptr<matvar_t, VarFreer>;

// matio writes its own header (platform, date) when given none; a fixed one
// keeps the file identical from run to run. MATLAB reads the version bytes,
// not this text, but expects the text to open like this.
constexpr const char* kHeader = "MATLAB 5.0 MAT-file, rigflex reduced frame";

void put(mat_t* mat, const char* name, const double* data, Eigen::Index rows, Eigen::Index cols,
         const fs::path& file) {
  size_t dims[2] = {static_cast<size_t>(rows), static_cast<size_t>(cols)};
  // matio takes a non-const pointer but only reads the data when writing.
  MatVar var(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(data),
                           MAT_F_DONT_COPY_DATA));
  if (!var || Mat_VarWrite(mat, var.get(), MAT_COMPRESSION_NONE) != 0)
    throw std::runtime_error("matio could not write the variable " + std::string(name) + " to " + file.string());
}

void put(mat_t* mat, const char* name, const Eigen::MatrixXd& A, const fs::path& file) {
  put(mat, name, A.data(), A.rows(), A.cols(), file);
}

void put(mat_t* mat, const char* name, const Eigen::VectorXd& v, const fs::path& file) {
  put(mat, name, v.data(), v.size(), 1, file);
}

void write_to(const fs::path& file, const ReducedMatVariables& v) {
  MatFile mat(Mat_CreateVer(file.string().c_str(), kHeader, MAT_FT_MAT5));
  if (!mat) throw std::runtime_error("matio could not create " + file.string());
  put(mat.get(), "K", v.K, file);
  put(mat.get(), "M", v.M, file);
  put(mat.get(), "C", v.C, file);
  put(mat.get(), "A", v.A, file);
  put(mat.get(), "B", v.B, file);
  put(mat.get(), "Css", v.Css, file);
  put(mat.get(), "D", v.D, file);
  put(mat.get(), "T", v.T, file);
  put(mat.get(), "interface_nodes", v.interface_nodes, file);
  put(mat.get(), "interface_coordinates", v.interface_coordinates, file);
  put(mat.get(), "dof_node", v.dof_node, file);
  put(mat.get(), "dof_index", v.dof_index, file);
  put(mat.get(), "alpha", &v.alpha, 1, 1, file);
  put(mat.get(), "beta", &v.beta, 1, 1, file);
  put(mat.get(), "mode_frequencies_hz", v.mode_frequencies_hz, file);
  // Closing flushes the file: its failure is a failed write.
  if (Mat_Close(mat.release()) != 0) throw std::runtime_error("matio could not finish writing " + file.string());
}

// matio reads a variable that a truncated file cuts short without a word,
// the missing bytes coming back as whatever was in memory. So the MAT 5
// layout is walked first: after the 128-byte header, each variable is an
// element with an 8-byte tag (type, byte count), and every one must fit in
// the file.
void require_whole_mat5(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char header[128];
  if (!in.read(reinterpret_cast<char*>(header), sizeof header))
    throw InputError(file.string(), 0, "", "cut short: no complete MAT header");
  // The writer stores 'M' 'I' as a 16-bit number: "IM" in a little-endian file.
  const bool little_endian = header[126] == 'I';
  auto u32 = [&](const unsigned char* b) -> std::uint64_t {
    return little_endian ? (std::uint64_t{b[3]} << 24 | std::uint64_t{b[2]} << 16 | std::uint64_t{b[1]} << 8 | b[0])
                         : (std::uint64_t{b[0]} << 24 | std::uint64_t{b[1]} << 16 | std::uint64_t{b[2]} << 8 | b[3]);
  };
  const std::uint64_t size = fs::file_size(file);
  std::uint64_t at = sizeof header;
  while (at < size) {
    unsigned char tag[8];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(tag), sizeof tag))
      throw InputError(file.string(), 0, "", "cut short: a variable's tag ends past the end of the file");
    const std::uint64_t first = u32(tag);
    // A "small data element" packs its byte count into the upper half of
    // the first word and its data into the second.
    at += (first >> 16) != 0 ? 8 : 8 + u32(tag + 4);
  }
  if (at > size)
    throw InputError(file.string(), 0, "", "cut short: the last variable ends " + std::to_string(at - size) +
                                               " bytes past the end of the file");
}

class MatReader {
 public:
  explicit MatReader(const fs::path& file) : file_(file.string()) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw InputError(file_, 0, "", "cannot open the file");
    mat_.reset(Mat_Open(file_.c_str(), MAT_ACC_RDONLY));
    if (!mat_) throw InputError(file_, 0, "", "not a MAT file (MATLAB 5 or 7.3 format)");
    // Version 7.3 files are HDF5, which finds damage itself.
    if (Mat_GetVersion(mat_.get()) == MAT_FT_MAT5) require_whole_mat5(file);
  }

  [[noreturn]] void fail(const std::string& variable, const std::string& message) const {
    throw InputError(file_, 0, variable, message);
  }

  Eigen::MatrixXd matrix(const char* name) const {
    MatVar var(Mat_VarRead(mat_.get(), name));
    if (!var) fail(name, "missing (or unreadable)");
    if (var->class_type != MAT_C_DOUBLE || var->isComplex || var->isLogical || var->data_size != sizeof(double))
      fail(name, "expected a real double matrix");
    if (var->rank != 2) fail(name, "expected a matrix, found " + std::to_string(var->rank) + " dimensions");
    Eigen::MatrixXd A(static_cast<Eigen::Index>(var->dims[0]), static_cast<Eigen::Index>(var->dims[1]));
    if (A.size() > 0) {
      if (!var->data) fail(name, "no data");
      std::memcpy(A.data(), var->data, static_cast<size_t>(A.size()) * sizeof(double));
    }
    return A;
  }

  // A row or a column (MATLAB users may save either); `count` -1: any length.
  Eigen::VectorXd vector(const char* name, Eigen::Index count = -1) const {
    const Eigen::MatrixXd A = matrix(name);
    if (A.size() > 0 && A.rows() != 1 && A.cols() != 1)
      fail(name, "expected a vector, found " + size_text(A.rows(), A.cols()));
    if (count >= 0 && A.size() != count)
      fail(name, "expected " + std::to_string(count) + " values, found " + std::to_string(A.size()));
    return A.reshaped();
  }

  bool has(const char* name) const {
    MatVar var(Mat_VarReadInfo(mat_.get(), name));
    return var != nullptr;
  }

  double scalar(const char* name) const {
    const Eigen::MatrixXd A = matrix(name);
    if (A.rows() != 1 || A.cols() != 1) fail(name, "expected a scalar, found " + size_text(A.rows(), A.cols()));
    return A(0, 0);
  }

  void require_size(const char* name, const Eigen::MatrixXd& A, Eigen::Index rows, Eigen::Index cols,
                    const std::string& why) const {
    if (A.rows() != rows || A.cols() != cols)
      fail(name, size_text(A.rows(), A.cols()) + ", expected " + size_text(rows, cols) + " (" + why + ")");
  }

  static std::string size_text(Eigen::Index rows, Eigen::Index cols) {
    return std::to_string(rows) + " x " + std::to_string(cols);
  }

 private:
  std::string file_;
  MatFile mat_;
};

}  // namespace

ReducedMatVariables reduced_mat_variables(const reduction::ReducedFrame& r) {
  check_exportable(r);
  ReducedMatVariables v;
  v.K = r.K;
  v.M = r.M;
  v.C = r.C;
  v.A = r.state_space.A;
  v.B = r.state_space.B;
  v.Css = r.state_space.C;
  v.D = r.state_space.D;
  v.T = r.state_space.T;
  const auto k = static_cast<Eigen::Index>(r.interface_nodes.size());
  v.interface_nodes.resize(k);
  v.interface_coordinates.resize(k, 3);
  for (Eigen::Index i = 0; i < k; ++i) {
    const auto& node = r.interface_nodes[static_cast<size_t>(i)];
    v.interface_nodes(i) = static_cast<double>(node.id);
    v.interface_coordinates.row(i) = node.position.transpose();
  }
  const Eigen::Index m = r.interface_dof_count();
  v.dof_node.resize(m);
  v.dof_index.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& dof = r.interface_dofs[static_cast<size_t>(i)];
    v.dof_node(i) = static_cast<double>(dof.node);
    v.dof_index(i) = dof.local + 1;
  }
  v.alpha = r.damping.alpha;
  v.beta = r.damping.beta;
  v.mode_frequencies_hz = r.mode_frequencies_hz;
  return v;
}

void write_reduced_mat(const fs::path& file, const ReducedMatVariables& v) {
  write_atomically(file, [&](const fs::path& temp) { write_to(temp, v); });
}

void add_reduced_mat_file(FileBatch& batch, const fs::path& file, const reduction::ReducedFrame& r) {
  batch.add(file, [v = reduced_mat_variables(r)](const fs::path& temp) { write_to(temp, v); });
}

ReducedMatVariables read_reduced_mat(const fs::path& file) {
  const MatReader in(file);
  ReducedMatVariables v;
  v.K = in.matrix("K");
  if (v.K.rows() != v.K.cols()) in.fail("K", "expected a square matrix, found " + in.size_text(v.K.rows(), v.K.cols()));
  const Eigen::Index n = v.K.rows();
  const std::string from_k = "K is " + in.size_text(n, n);
  v.M = in.matrix("M");
  in.require_size("M", v.M, n, n, from_k);
  v.C = in.matrix("C");
  in.require_size("C", v.C, n, n, from_k);

  v.interface_nodes = in.vector("interface_nodes");
  const Eigen::Index k = v.interface_nodes.size();
  v.interface_coordinates = in.matrix("interface_coordinates");
  in.require_size("interface_coordinates", v.interface_coordinates, k, 3,
                  std::to_string(k) + " interface nodes, x y z each");
  v.dof_node = in.vector("dof_node");
  const Eigen::Index m = v.dof_node.size();
  v.dof_index = in.vector("dof_index", m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const double d = v.dof_index(i);
    if (!(d >= 1 && d <= 6 && d == std::floor(d)))
      in.fail("dof_index", "entry " + std::to_string(i + 1) + " is not one of 1..6 (UX UY UZ RX RY RZ)");
    const auto& ids = v.interface_nodes;
    if (std::find(ids.begin(), ids.end(), v.dof_node(i)) == ids.end())
      in.fail("dof_node", "entry " + std::to_string(i + 1) + " is not one of interface_nodes");
  }
  v.mode_frequencies_hz = in.vector("mode_frequencies_hz");
  if (m + v.mode_frequencies_hz.size() != n)
    in.fail("mode_frequencies_hz", std::to_string(v.mode_frequencies_hz.size()) + " modes and " + std::to_string(m) +
                                       " interface DOFs (dof_node) do not add up to the " + std::to_string(n) +
                                       " rows of K");
  const std::string from_nm = std::to_string(m) + " interface DOFs + " +
                              std::to_string(v.mode_frequencies_hz.size()) + " modes";
  v.A = in.matrix("A");
  in.require_size("A", v.A, 2 * n, 2 * n, from_nm);
  v.B = in.matrix("B");
  in.require_size("B", v.B, 2 * n, m, from_nm);
  v.Css = in.matrix("Css");
  in.require_size("Css", v.Css, 2 * m, 2 * n, from_nm);
  v.D = in.matrix("D");
  in.require_size("D", v.D, 2 * m, m, from_nm);
  if (in.has("T")) {
    v.T = in.matrix("T");
    in.require_size("T", v.T, n, n, from_k);
  } else {
    v.T = Eigen::MatrixXd::Identity(n, n);
  }
  v.alpha = in.scalar("alpha");
  v.beta = in.scalar("beta");
  return v;
}

}  // namespace rigflex::io
