// bonmin_mps: solve a free-MPS MIQP (QUADOBJ section) with Bonmin's branch-and-bound.
//
//   bonmin_mps FILE.mps [--time-limit S] [--mip-gap G] [--algorithm B-BB|B-OA|B-QG|B-Hyb]
//              [--verbose]
//
// Prints one JSON line on stdout, the same fields as solve_mps.py:
//   {"solver","version","status","time_s","objective","bound","message"}
// status is optimal | feasible | time_limit | infeasible | error. The objective is the
// MPS objective c'x + 0.5 x'Qx: a constant term (an RHS on the objective row) is not
// added, as with the other peers. Bonmin is single-threaded; Ipopt uses sequential MUMPS.
//
// QUADOBJ convention (CPLEX's, as mfp writes it): each entry (i, j, v) of one triangle is
// listed once and stands for Q_ij = Q_ji = v; the objective is c'x + 0.5 x'Qx. CoinMpsIO
// returns the entries as listed; this driver mirrors the off-diagonal ones itself.

#include <BonBonminSetup.hpp>
#include <BonCbc.hpp>
#include <BonTMINLP.hpp>
#include <BonminConfig.h>
#include <CoinMpsIO.hpp>
#include <CoinPackedMatrix.hpp>
#include <IpoptConfig.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

// A sparse MIQP: min c'x + 0.5 x'Qx  s.t.  row_lower <= A x <= row_upper, bounds, integrality.
struct MpsMiqp {
  int num_cols = 0;
  int num_rows = 0;
  std::vector<double> c;
  std::vector<double> col_lower, col_upper;
  std::vector<bool> is_integer;
  std::vector<double> row_lower, row_upper;
  // A in triplet form, row-major order.
  std::vector<int> a_row, a_col;
  std::vector<double> a_val;
  // Lower triangle of the symmetric Q (q_row >= q_col).
  std::vector<int> q_row, q_col;
  std::vector<double> q_val;
  double objective_constant = 0.0;  // read, reported, never added
};

// CoinMpsIO guesses fixed or free MPS from column positions, and guesses wrong on free MPS
// with short names (" UP bnd x 3" is read as a fixed-format card). Its explicit switch is
// the word FREE after the problem name on the NAME card: this writes a copy of the file
// with that word added to temp_path. Returns an empty string on success, else the reason.
std::string CopyAsExplicitFreeMps(const std::string& path, const std::string& temp_path) {
  std::ifstream in(path);
  if (!in) return "cannot open " + path;
  std::ofstream out(temp_path);
  if (!out) return "cannot write " + temp_path;
  std::string line;
  bool name_seen = false;
  while (std::getline(in, line)) {
    if (!name_seen && !line.empty() && line[0] != '*' && line[0] != ' ' && line[0] != '\t') {
      name_seen = true;
      std::istringstream words(line);
      std::string keyword, name, extra;
      words >> keyword >> name >> extra;
      if (keyword == "NAME") {
        if (extra != "FREE") line = "NAME " + (name.empty() ? std::string("mps") : name) + " FREE";
      } else {
        out << "NAME mps FREE\n";
      }
    }
    out << line << '\n';
  }
  return out ? "" : "cannot write " + temp_path;
}

// Takes the problem out of a reader whose readMps stopped at the QUADOBJ section (or at
// ENDATA), then reads that section.
std::string ReadMpsFrom(CoinMpsIO& reader, int errors, const std::string& path, MpsMiqp* out) {
  if (errors != 0) {
    return "CoinMpsIO::readMps reported " + std::to_string(errors) + " error(s) reading " + path;
  }
  MpsMiqp& p = *out;
  p.num_cols = reader.getNumCols();
  p.num_rows = reader.getNumRows();
  p.c.assign(reader.getObjCoefficients(), reader.getObjCoefficients() + p.num_cols);
  p.col_lower.assign(reader.getColLower(), reader.getColLower() + p.num_cols);
  p.col_upper.assign(reader.getColUpper(), reader.getColUpper() + p.num_cols);
  p.row_lower.assign(reader.getRowLower(), reader.getRowLower() + p.num_rows);
  p.row_upper.assign(reader.getRowUpper(), reader.getRowUpper() + p.num_rows);
  p.is_integer.resize(p.num_cols);
  for (int j = 0; j < p.num_cols; ++j) p.is_integer[j] = reader.isInteger(j);
  // Whatever CoinMpsIO makes of an RHS on the objective row (readers disagree on its sign);
  // mfp writes none and keeps the constant in its plan JSON.
  p.objective_constant = reader.objectiveOffset();

  const CoinPackedMatrix* rows = reader.getMatrixByRow();
  for (int i = 0; i < p.num_rows; ++i) {
    const CoinBigIndex start = rows->getVectorStarts()[i];
    const int length = rows->getVectorLengths()[i];
    for (CoinBigIndex k = start; k < start + length; ++k) {
      p.a_row.push_back(i);
      p.a_col.push_back(rows->getIndices()[k]);
      p.a_val.push_back(rows->getElements()[k]);
    }
  }

  CoinBigIndex* q_start = nullptr;
  int* q_index = nullptr;
  double* q_elem = nullptr;
  const int q_errors = reader.readQuadraticMps(nullptr, q_start, q_index, q_elem, 0);
  if (q_errors == -2 || q_errors == -3) {
    return "";  // no (or an empty) QUADOBJ section: a linear objective
  }
  if (q_errors != 0) {
    return "CoinMpsIO::readQuadraticMps reported " + std::to_string(q_errors) + " reading " + path;
  }
  // (row >= col) -> Q value. An entry listed as both (i, j) and (j, i) is summed, as a
  // triangle should list each entry once.
  std::map<std::pair<int, int>, double> lower;
  for (int j = 0; j < p.num_cols; ++j) {
    for (CoinBigIndex k = q_start[j]; k < q_start[j + 1]; ++k) {
      const int i = q_index[k];
      lower[{std::max(i, j), std::min(i, j)}] += q_elem[k];
    }
  }
  delete[] q_start;
  delete[] q_index;
  delete[] q_elem;
  for (const auto& [key, value] : lower) {
    if (value == 0.0) continue;
    p.q_row.push_back(key.first);
    p.q_col.push_back(key.second);
    p.q_val.push_back(value);
  }
  return "";
}

// Reads FILE.mps; returns an empty string on success, else the reason.
std::string ReadMps(const std::string& path, bool verbose, MpsMiqp* out) {
  char temp_path[] = "/tmp/bonmin_mps_XXXXXX";
  const int temp_fd = mkstemp(temp_path);
  if (temp_fd < 0) return "cannot create a temporary file in /tmp";
  close(temp_fd);
  const std::string copy_error = CopyAsExplicitFreeMps(path, temp_path);
  if (!copy_error.empty()) {
    unlink(temp_path);
    return copy_error;
  }
  CoinMpsIO reader;
  reader.messageHandler()->setLogLevel(verbose ? 1 : 0);
  const int errors = reader.readMps(temp_path, "");
  const std::string why = ReadMpsFrom(reader, errors, path, out);
  unlink(temp_path);
  return why;
}

// The MIQP as a Bonmin TMINLP; linear constraints, quadratic objective.
class MiqpTminlp final : public Bonmin::TMINLP {
 public:
  explicit MiqpTminlp(const MpsMiqp& p) : p_(p), in_quadratic_(p.num_cols, false) {
    for (size_t k = 0; k < p_.q_row.size(); ++k) {
      in_quadratic_[p_.q_row[k]] = true;
      in_quadratic_[p_.q_col[k]] = true;
    }
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, Ipopt::TNLP::IndexStyleEnum& index_style) override {
    n = p_.num_cols;
    m = p_.num_rows;
    nnz_jac_g = static_cast<Ipopt::Index>(p_.a_val.size());
    nnz_h_lag = static_cast<Ipopt::Index>(p_.q_val.size());
    index_style = Ipopt::TNLP::C_STYLE;
    return true;
  }

  bool get_variables_types(Ipopt::Index n, VariableType* var_types) override {
    for (Ipopt::Index j = 0; j < n; ++j) {
      if (!p_.is_integer[j]) {
        var_types[j] = CONTINUOUS;
      } else if (p_.col_lower[j] == 0.0 && p_.col_upper[j] == 1.0) {
        var_types[j] = BINARY;
      } else {
        var_types[j] = INTEGER;
      }
    }
    return true;
  }

  bool get_variables_linearity(Ipopt::Index n, Ipopt::TNLP::LinearityType* types) override {
    for (Ipopt::Index j = 0; j < n; ++j) {
      types[j] = in_quadratic_[j] ? Ipopt::TNLP::NON_LINEAR : Ipopt::TNLP::LINEAR;
    }
    return true;
  }

  bool get_constraints_linearity(Ipopt::Index m, Ipopt::TNLP::LinearityType* types) override {
    std::fill(types, types + m, Ipopt::TNLP::LINEAR);
    return true;
  }

  bool get_bounds_info(Ipopt::Index, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override {
    std::copy(p_.col_lower.begin(), p_.col_lower.end(), x_l);
    std::copy(p_.col_upper.begin(), p_.col_upper.end(), x_u);
    std::copy(p_.row_lower.begin(), p_.row_lower.end(), g_l);
    std::copy(p_.row_upper.begin(), p_.row_upper.end(), g_u);
    return true;
  }

  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number*, Ipopt::Number*, Ipopt::Index, bool init_lambda,
                          Ipopt::Number*) override {
    if (init_z || init_lambda) return false;
    if (init_x) {
      for (Ipopt::Index j = 0; j < n; ++j) {
        x[j] = std::min(std::max(0.0, p_.col_lower[j]), p_.col_upper[j]);
      }
    }
    return true;
  }

  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number& f) override {
    f = 0.0;
    for (Ipopt::Index j = 0; j < n; ++j) f += p_.c[j] * x[j];
    for (size_t k = 0; k < p_.q_val.size(); ++k) {
      const int i = p_.q_row[k], j = p_.q_col[k];
      f += (i == j ? 0.5 : 1.0) * p_.q_val[k] * x[i] * x[j];
    }
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number* g) override {
    std::copy(p_.c.begin(), p_.c.begin() + n, g);
    for (size_t k = 0; k < p_.q_val.size(); ++k) {
      const int i = p_.q_row[k], j = p_.q_col[k];
      g[i] += p_.q_val[k] * x[j];
      if (i != j) g[j] += p_.q_val[k] * x[i];
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index m,
              Ipopt::Number* g) override {
    std::fill(g, g + m, 0.0);
    for (size_t k = 0; k < p_.a_val.size(); ++k) g[p_.a_row[k]] += p_.a_val[k] * x[p_.a_col[k]];
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* i_row, Ipopt::Index* j_col, Ipopt::Number* values) override {
    if (values == nullptr) {
      std::copy(p_.a_row.begin(), p_.a_row.end(), i_row);
      std::copy(p_.a_col.begin(), p_.a_col.end(), j_col);
    } else {
      std::copy(p_.a_val.begin(), p_.a_val.end(), values);
    }
    return true;
  }

  bool eval_h(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Number obj_factor, Ipopt::Index,
              const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index* i_row, Ipopt::Index* j_col,
              Ipopt::Number* values) override {
    if (values == nullptr) {
      std::copy(p_.q_row.begin(), p_.q_row.end(), i_row);
      std::copy(p_.q_col.begin(), p_.q_col.end(), j_col);
    } else {
      for (size_t k = 0; k < p_.q_val.size(); ++k) values[k] = obj_factor * p_.q_val[k];
    }
    return true;
  }

  void finalize_solution(TMINLP::SolverReturn, Ipopt::Index, const Ipopt::Number*,
                         Ipopt::Number) override {}

  const BranchingInfo* branchingInfo() const override { return nullptr; }
  const SosInfo* sosConstraints() const override { return nullptr; }

 private:
  const MpsMiqp& p_;
  std::vector<bool> in_quadratic_;
};

std::string JsonNumber(double v) {
  if (!std::isfinite(v) || std::fabs(v) >= 1e20) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      out += ' ';
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// Writes the result line to fd (the real stdout, saved before the solver's output was
// redirected).
void PrintResult(int fd, const std::string& status, double time_s, double objective, double bound,
                 const std::string& message) {
  std::ostringstream line;
  line << "{\"solver\": \"bonmin\", \"version\": \"Bonmin " << BONMIN_VERSION << " (Ipopt "
       << IPOPT_VERSION << ")\", \"status\": " << JsonString(status)
       << ", \"time_s\": " << JsonNumber(time_s) << ", \"objective\": " << JsonNumber(objective)
       << ", \"bound\": " << JsonNumber(bound) << ", \"message\": " << JsonString(message) << "}\n";
  const std::string text = line.str();
  if (write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) std::exit(1);
}

int Usage(const char* why) {
  std::fprintf(stderr,
               "bonmin_mps: %s\nusage: bonmin_mps FILE.mps [--time-limit S] [--mip-gap G] "
               "[--algorithm B-BB|B-OA|B-QG|B-Hyb] [--verbose]\n",
               why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  double time_limit_s = 60.0;
  double mip_gap = -1.0;  // < 0: Bonmin's default
  std::string algorithm = "B-BB";
  bool verbose = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if ((arg == "--time-limit" || arg == "--mip-gap" || arg == "--algorithm") && a + 1 < argc) {
      const std::string value = argv[++a];
      if (arg == "--algorithm") {
        algorithm = value;
        continue;
      }
      char* end = nullptr;
      const double number = std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0' || !(number >= 0.0)) {
        return Usage((arg + " needs a number >= 0, got '" + value + "'").c_str());
      }
      (arg == "--time-limit" ? time_limit_s : mip_gap) = number;
    } else if (arg == "--verbose") {
      verbose = true;
    } else if (!arg.empty() && arg[0] != '-' && path.empty()) {
      path = arg;
    } else {
      return Usage(("unexpected argument '" + arg + "'").c_str());
    }
  }
  if (path.empty()) return Usage("no MPS file given");
  if (time_limit_s <= 0.0) return Usage("--time-limit must be > 0");

  // From here on Bonmin, Cbc and Ipopt print on fd 1: keep the real stdout for the result.
  std::fflush(stdout);
  const int result_fd = dup(1);
  const int sink = verbose ? dup(2) : open("/dev/null", O_WRONLY);
  dup2(sink, 1);
  close(sink);

  MpsMiqp problem;
  const std::string read_error = ReadMps(path, verbose, &problem);
  if (!read_error.empty()) {
    PrintResult(result_fd, "error", NAN, NAN, NAN, read_error);
    return 1;
  }

  std::ostringstream message;
  const auto start = std::chrono::steady_clock::now();
  double objective = NAN, bound = NAN;
  std::string status;
  try {
    Bonmin::BonminSetup setup;
    setup.initializeOptionsAndJournalist();
    std::ostringstream options;
    options << "bonmin.algorithm " << algorithm << "\n"
            << "bonmin.time_limit " << time_limit_s << "\n"
            << "bonmin.bb_log_level " << (verbose ? 1 : 0) << "\n"
            << "bonmin.nlp_log_level " << (verbose ? 1 : 0) << "\n"
            << "print_level " << (verbose ? 3 : 0) << "\n"
            << "sb yes\n";
    if (mip_gap >= 0.0) options << "bonmin.allowable_fraction_gap " << mip_gap << "\n";
    setup.readOptionsString(options.str());  // also keeps a stray bonmin.opt from being read
    Ipopt::SmartPtr<Bonmin::TMINLP> tminlp = new MiqpTminlp(problem);
    setup.initialize(tminlp);
    Bonmin::Bab bab;
    bab(setup);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool has_solution = bab.bestSolution() != nullptr;
    objective = has_solution ? bab.bestObj() : NAN;
    bound = bab.bestBound();
    switch (bab.mipStatus()) {
      case Bonmin::Bab::FeasibleOptimal:
        status = "optimal";
        break;
      case Bonmin::Bab::ProvenInfeasible:
        status = "infeasible";
        bound = NAN;
        break;
      case Bonmin::Bab::Feasible:
      case Bonmin::Bab::NoSolutionKnown:
        status = elapsed >= 0.98 * time_limit_s ? "time_limit" : (has_solution ? "feasible" : "error");
        break;
      default:
        status = "error";
        break;
    }
    message << "Bonmin " << algorithm << " mipStatus " << static_cast<int>(bab.mipStatus())
            << ", nodes " << bab.numNodes();
    if (problem.objective_constant != 0.0) {
      message << "; objective row RHS gives constant " << problem.objective_constant
              << " (not added)";
    }
    PrintResult(result_fd, status, elapsed, objective, bound, message.str());
  } catch (const Bonmin::TNLPSolver::UnsolvedError* e) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PrintResult(result_fd, "error", elapsed, NAN, NAN,
                "Ipopt failed on a node: " + e->errorName());
    return 1;
  } catch (const CoinError& e) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PrintResult(result_fd, "error", elapsed, NAN, NAN,
                "CoinError in " + e.className() + "::" + e.methodName() + ": " + e.message());
    return 1;
  }
  return 0;
}
