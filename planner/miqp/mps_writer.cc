#include "planner/miqp/mps_writer.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <vector>

#include "base/check.h"

namespace mfp {
namespace {

constexpr const char* kObjectiveRow = "OBJ";

}  // namespace

void WriteMps(const Miqp& p, const std::string& name, std::ostream& out) {
  CheckMiqpShape(p);
  out << std::setprecision(17);
  out << "NAME " << name << "\n";
  out << "ROWS\n";
  out << " N " << kObjectiveRow << "\n";
  std::vector<bool> row_written(p.num_rows(), false);
  for (int i = 0; i < p.num_rows(); ++i) {
    const double lo = p.row_lower(i), hi = p.row_upper(i);
    const char* type = nullptr;
    if (std::isfinite(lo) && std::isfinite(hi)) {
      type = lo == hi ? "E" : "L";  // a ranged row is L with RANGES
    } else if (std::isfinite(hi)) {
      type = "L";
    } else if (std::isfinite(lo)) {
      type = "G";
    }
    if (type == nullptr) continue;  // a free row constrains nothing
    row_written[i] = true;
    out << " " << type << " " << p.row_names[i] << "\n";
  }
  // Columns: the column-major view of A.
  const Eigen::SparseMatrix<double> a_cols(p.A);
  out << "COLUMNS\n";
  bool in_integer_block = false;
  int marker = 0;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.is_integer[j] != in_integer_block) {
      out << " MARKER" << marker++ << " 'MARKER' '" << (p.is_integer[j] ? "INTORG" : "INTEND") << "'\n";
      in_integer_block = p.is_integer[j];
    }
    const std::string& col = p.var_names[j];
    bool any = false;
    if (p.c(j) != 0.0) {
      out << " " << col << " " << kObjectiveRow << " " << p.c(j) << "\n";
      any = true;
    }
    for (Eigen::SparseMatrix<double>::InnerIterator it(a_cols, j); it; ++it) {
      if (!row_written[it.row()] || it.value() == 0.0) continue;
      out << " " << col << " " << p.row_names[it.row()] << " " << it.value() << "\n";
      any = true;
    }
    // A column must appear in COLUMNS to exist; give an unused one a zero objective entry.
    if (!any) out << " " << col << " " << kObjectiveRow << " 0\n";
  }
  if (in_integer_block) out << " MARKER" << marker++ << " 'MARKER' 'INTEND'\n";
  out << "RHS\n";
  for (int i = 0; i < p.num_rows(); ++i) {
    if (!row_written[i]) continue;
    const double lo = p.row_lower(i), hi = p.row_upper(i);
    const double rhs = std::isfinite(hi) ? hi : lo;
    if (rhs != 0.0) out << " RHS " << p.row_names[i] << " " << rhs << "\n";
  }
  out << "RANGES\n";
  for (int i = 0; i < p.num_rows(); ++i) {
    const double lo = p.row_lower(i), hi = p.row_upper(i);
    if (row_written[i] && std::isfinite(lo) && std::isfinite(hi) && lo != hi) {
      out << " RNG " << p.row_names[i] << " " << (hi - lo) << "\n";
    }
  }
  out << "BOUNDS\n";
  for (int j = 0; j < p.num_variables(); ++j) {
    const std::string& col = p.var_names[j];
    const double lo = p.var_lower(j), hi = p.var_upper(j);
    if (std::isinf(lo) && std::isinf(hi)) {
      out << " FR BND " << col << "\n";
    } else if (lo == hi) {
      out << " FX BND " << col << " " << lo << "\n";
    } else {
      if (std::isfinite(lo)) {
        out << " LO BND " << col << " " << lo << "\n";
      } else {
        out << " MI BND " << col << "\n";
      }
      if (std::isfinite(hi)) {
        out << " UP BND " << col << " " << hi << "\n";
      } else {
        out << " PL BND " << col << "\n";
      }
    }
  }
  out << "QUADOBJ\n";
  for (int col = 0; col < p.Q.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.Q, col); it; ++it) {
      if (it.row() <= it.col() && it.value() != 0.0) {
        out << " " << p.var_names[it.row()] << " " << p.var_names[it.col()] << " " << it.value() << "\n";
      }
    }
  }
  out << "ENDATA\n";
}

void WriteMpsFile(const Miqp& problem, const std::string& name, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot open for writing");
  WriteMps(problem, name, file);
  file.flush();
  if (!file) throw InputError(path + ": write failed");
}

}  // namespace mfp
