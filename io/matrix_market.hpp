#pragma once
// Dense matrices in Matrix Market text (https://math.nist.gov/MatrixMarket/).
//
// Written: `%%MatrixMarket matrix array real general`, '%' comment lines, the
// size line, then the values column by column, one per line, each with 17
// significant digits, which is enough for every double (normal or subnormal,
// and -0) to read back bit for bit. NaN and infinities have no Matrix Market
// spelling that other readers agree on, so writing one is an error.
//
// Read: array and coordinate formats; real and integer fields; general,
// symmetric and skew-symmetric storage (only the lower triangle is stored,
// the upper one is filled in). Complex, pattern and hermitian files are
// refused, as are repeated coordinate entries (other readers add them up,
// some keep the last: neither is safe to guess).
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

namespace rigflex::io {

// `comment` may span several lines; each becomes a '%' line after the header.
// Throws std::invalid_argument naming the entry (1-based row, column) for a
// NaN or an infinity.
std::string matrix_market_text(const Eigen::MatrixXd& A, const std::string& comment);
// matrix_market_text written atomically.
void write_matrix_market(const std::filesystem::path& file, const Eigen::MatrixXd& A, const std::string& comment);

// The size a reader requires, and where that requirement comes from (for the
// message, e.g. "12 interface DOFs + 4 modes in reduced.json").
struct MatrixShape {
  Eigen::Index rows = 0;
  Eigen::Index cols = 0;
  std::string origin;
};

// Throws InputError naming `source` and the line: a bad header or size line,
// a value that is not a number (or not finite, or not an integer in an
// integer file), too few or too many values, an entry out of range or
// repeated, a stored upper-triangle entry of a symmetric matrix, or a size
// other than `expected` (reported at the size line, before anything is
// allocated).
Eigen::MatrixXd parse_matrix_market(const std::string& text, const std::string& source,
                                    const std::optional<MatrixShape>& expected = std::nullopt);
Eigen::MatrixXd read_matrix_market(const std::filesystem::path& file,
                                   const std::optional<MatrixShape>& expected = std::nullopt);

}  // namespace rigflex::io
