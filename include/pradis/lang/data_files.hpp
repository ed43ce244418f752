#pragma once
/// \file
/// Data read from other files by a $DATA value list (docs/language.md):
///
/// - `FILE("table.csv")`: the numbers of a two-column table file
///   (io::parse_table_csv), x1, y1, x2, y2, ...;
/// - `CRAIGBAMPTON("k.mtx", "m.mtx", modes, dof, dof, ...)`: the stiffness and
///   mass matrices of a linear elastic part from Matrix Market files
///   (io/matrix_market.hpp), reduced to the boundary DOFs and `modes`
///   fixed-interface modes (linalg::craig_bampton), as the lower triangles of
///   K_r and M_r row by row: FLEX3's parameters after its node positions.
///
/// Errors inside a data file are located in it (file:line:column, its line and a
/// caret) and name the call; errors of the call's arguments at the argument.
/// Also the file reading the parser uses for them and for $INCLUDE.

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/io/matrix_market.hpp"
#include "pradis/io/table_csv.hpp"
#include "pradis/lang/ast.hpp"
#include "pradis/lang/source.hpp"
#include "pradis/linalg/reduction.hpp"

namespace pradis::lang {

/// Reads an included file by its (resolved) path; nothing if it cannot be read.
using file_loader = std::function<std::optional<std::string>(const std::string& path)>;

/// Reads a file from disk (binary, whole); nothing if it cannot be read (errno
/// then tells why).
inline std::optional<std::string> read_file(const std::string& path) {
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  std::ostringstream os;
  os << f.rdbuf();
  if (f.bad()) return std::nullopt;
  return os.str();
}

/// ": <the system's reason>" for the last failed file operation (errno), or "".
inline std::string os_reason() {
  const int e = errno;
  return e == 0 ? std::string() : std::string(": ") + std::strerror(e);
}

/// One data file named by a call: its resolved name, its text and where the
/// name stands in the model file.
struct data_file {
  std::string name;
  std::string text;
  location loc;
};

namespace detail {
/// Re-throws a defect `e` found in the data file `f` as a lang_error at its line
/// and column there (at the file name in the model file if it has no line),
/// naming the call: "... (in the <what> read by <call> at model.prd:l:c)".
[[noreturn]] inline void rethrow_in_file(const io::table_csv_error& e, const data_file& f, const location& call,
                                         const std::string& what) {
  const std::string msg = e.detail() + " (in the " + what + " at " + call.str() + ")";
  if (e.line() <= 0) throw lang_error(f.loc, msg);
  auto src = std::make_shared<const source_file>(source_file{f.name, f.text});
  throw lang_error(location{src, e.line(), e.column()}, msg);
}

/// A number as the model file would write it (6 significant digits).
inline std::string show(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

inline void push_number(double x, const location& where, std::vector<ast::item>& out) {
  ast::item v;
  v.loc = where;
  v.number = x;
  out.push_back(std::move(v));
}
}  // namespace detail

/// Appends x1, y1, x2, y2, ... of the table file `f` to `out` as number items
/// located at `where` (the FILE call). Throws lang_error at the bad cell of the
/// table file, or at the file name if the file has no data lines.
inline void table_file_items(const data_file& f, const location& where, std::vector<ast::item>& out) {
  std::vector<double> numbers;
  try {
    numbers = io::parse_table_csv(f.text, f.name);
  } catch (const io::table_csv_error& e) {
    detail::rethrow_in_file(e, f, where, "table file read by FILE");
  }
  for (const double x : numbers) detail::push_number(x, where, out);
}

/// The largest part CRAIGBAMPTON reduces: the reduction is dense (an n x n
/// Cholesky factorisation and eigenproblem), so larger parts belong in C++
/// with linalg::craig_bampton on matrices already reduced by other means.
inline constexpr long craig_bampton_max_dofs = 3000;

/// CRAIGBAMPTON: reads K (`k`) and M (`m`), reduces them to the boundary DOFs
/// `args[1..]` (1-based row numbers of the matrices, in the order of the reduced
/// coordinates) and `args[0]` fixed-interface modes, and appends the lower
/// triangles of K_r and M_r, row by row, to `out` as number items located at
/// `where` (the call). Throws lang_error: at the argument for a count or DOF
/// that is not a whole number in range or a DOF given twice; in the matrix file
/// for a Matrix Market defect; at the call for matrices that do not fit each
/// other or cannot be reduced (the message of linalg::craig_bampton).
inline void craig_bampton_items(const data_file& k, const data_file& m, const std::vector<ast::item>& args,
                                const location& where, std::vector<ast::item>& out) {
  const auto read = [&](const data_file& f) {
    try {
      return io::parse_matrix_market(f.text, f.name, craig_bampton_max_dofs);
    } catch (const io::table_csv_error& e) {
      detail::rethrow_in_file(e, f, where, "matrix file read by CRAIGBAMPTON");
    }
  };
  const Eigen::MatrixXd kk = read(k), mm = read(m);
  if (args.size() < 2)
    throw lang_error(where, "CRAIGBAMPTON needs the number of modes and at least one boundary DOF after the two "
                            "matrix files: CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", modes, dof, dof, ...)");
  const auto whole = [](double x, double lo, double hi) { return x >= lo && x <= hi && x == std::floor(x); };
  const double n = static_cast<double>(kk.rows());
  const ast::item& modes = args[0];
  if (!whole(modes.number, 0, n))
    throw lang_error(modes.loc, "the number of modes of CRAIGBAMPTON must be a whole number in 0.." +
                                    std::to_string(kk.rows()) + ", found " + detail::show(modes.number));
  std::vector<int> boundary;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const double d = args[i].number;
    if (!whole(d, 1, n))
      throw lang_error(args[i].loc, "boundary DOF " + detail::show(d) + " of CRAIGBAMPTON is not a whole number in 1.." +
                                        std::to_string(kk.rows()) + " (the rows of '" + k.name + "')");
    const int row = static_cast<int>(d) - 1;
    for (std::size_t j = 0; j < boundary.size(); ++j)
      if (boundary[j] == row)
        throw lang_error(args[i].loc, "boundary DOF " + detail::show(d) + " of CRAIGBAMPTON is given twice (also " +
                                          "as boundary DOF " + std::to_string(j + 1) + ")");
    boundary.push_back(row);
  }
  linalg::reduced_part r;
  try {
    r = linalg::craig_bampton(kk, mm, boundary, static_cast<int>(modes.number));
  } catch (const error& e) {
    std::string why = e.message();
    if (why.rfind("craig_bampton: ", 0) == 0) why.erase(0, 15);
    throw lang_error(where, "CRAIGBAMPTON cannot reduce '" + k.name + "' and '" + m.name + "': " + why);
  }
  for (const Eigen::MatrixXd* a : {&r.k, &r.m})
    for (Eigen::Index row = 0; row < a->rows(); ++row)
      for (Eigen::Index col = 0; col <= row; ++col) detail::push_number((*a)(row, col), where, out);
}

}  // namespace pradis::lang
