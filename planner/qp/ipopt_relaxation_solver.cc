#include "planner/qp/internal/ipopt_relaxation_solver.h"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>

#include "base/check.h"
#include "planner/qp/internal/fixed_variable_reduction.h"

namespace mfp {
namespace {

constexpr double kIpoptInfinity = 1e19;
// Rows are satisfied within this (Ipopt's own constraint tolerance is 1e-4 by default,
// its interior-point iterates end within ~1e-8).
constexpr double kRowTolerance = 1e-6;

double ToIpopt(double bound) {
  return std::isinf(bound) ? (bound > 0 ? kIpoptInfinity : -kIpoptInfinity) : bound;
}

// The relaxation as an Ipopt TNLP: quadratic objective, linear constraints, both with
// constant derivatives (Ipopt is told so and evaluates them once).
class QpTnlp final : public Ipopt::TNLP {
 public:
  QpTnlp(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
         const Eigen::VectorXd* warm_start, const Deadline& deadline)
      : p_(problem), lower_(lower), upper_(upper), deadline_(deadline) {
    if (warm_start != nullptr) start_ = *warm_start;
    // Lower triangle of Q in column-major order.
    for (int col = 0; col < p_.Q.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(p_.Q, col); it; ++it) {
        if (it.row() >= it.col()) {
          h_rows_.push_back(static_cast<int>(it.row()));
          h_cols_.push_back(static_cast<int>(it.col()));
          h_vals_.push_back(it.value());
        }
      }
    }
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = p_.num_variables();
    m = p_.num_rows();
    nnz_jac_g = static_cast<Ipopt::Index>(p_.A.nonZeros());
    nnz_h_lag = static_cast<Ipopt::Index>(h_vals_.size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override {
    for (Ipopt::Index j = 0; j < n; ++j) {
      x_l[j] = ToIpopt(lower_(j));
      x_u[j] = ToIpopt(upper_(j));
    }
    for (Ipopt::Index i = 0; i < m; ++i) {
      g_l[i] = ToIpopt(p_.row_lower(i));
      g_u[i] = ToIpopt(p_.row_upper(i));
    }
    return true;
  }

  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number*, Ipopt::Number*, Ipopt::Index, bool init_lambda,
                          Ipopt::Number*) override {
    MFP_CHECK(init_x && !init_z && !init_lambda);
    for (Ipopt::Index j = 0; j < n; ++j) {
      double v = start_.size() == n ? start_(j) : 0.0;
      if (start_.size() != n) {
        // Cold start: middle of finite bounds, else the finite bound, else zero.
        const bool lf = std::isfinite(lower_(j)), uf = std::isfinite(upper_(j));
        v = lf && uf ? 0.5 * (lower_(j) + upper_(j)) : lf ? lower_(j) : uf ? upper_(j) : 0.0;
      }
      x[j] = std::clamp(v, lower_(j), upper_(j));
    }
    return true;
  }

  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number& obj) override {
    const Eigen::Map<const Eigen::VectorXd> xv(x, n);
    obj = 0.5 * xv.dot(p_.Q * xv) + p_.c.dot(xv) + p_.constant;
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number* grad) override {
    const Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd>(grad, n) = p_.Q * xv + p_.c;
    return true;
  }

  bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Index m,
              Ipopt::Number* g) override {
    const Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd>(g, m) = p_.A * xv;
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values) override {
    Ipopt::Index k = 0;
    for (int row = 0; row < p_.A.outerSize(); ++row) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p_.A, row); it; ++it, ++k) {
        if (values == nullptr) {
          rows[k] = static_cast<Ipopt::Index>(it.row());
          cols[k] = static_cast<Ipopt::Index>(it.col());
        } else {
          values[k] = it.value();
        }
      }
    }
    return true;
  }

  bool eval_h(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Number obj_factor, Ipopt::Index,
              const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index* rows, Ipopt::Index* cols,
              Ipopt::Number* values) override {
    for (size_t k = 0; k < h_vals_.size(); ++k) {
      if (values == nullptr) {
        rows[k] = h_rows_[k];
        cols[k] = h_cols_[k];
      } else {
        values[k] = obj_factor * h_vals_[k];
      }
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number obj_value,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solver_return_ = status;
    x_ = Eigen::Map<const Eigen::VectorXd>(x, n);
    objective_ = obj_value;
  }

  // Called by Ipopt after every iteration: false stops it (User_Requested_Stop), so a
  // deadline or a stop flag holds inside a solve, on wall time (max_cpu_time counts CPU).
  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    return !deadline_.Expired();
  }

  Ipopt::SolverReturn solver_return() const { return solver_return_; }
  const Eigen::VectorXd& x() const { return x_; }
  double objective() const { return objective_; }

 private:
  const Miqp& p_;
  const Eigen::VectorXd& lower_;
  const Eigen::VectorXd& upper_;
  Eigen::VectorXd start_;
  const Deadline deadline_;
  std::vector<int> h_rows_, h_cols_;
  std::vector<double> h_vals_;
  Ipopt::SolverReturn solver_return_ = Ipopt::INTERNAL_ERROR;
  Eigen::VectorXd x_;
  double objective_ = 0.0;
};

class IpoptRelaxationSolver final : public RelaxationSolver {
 public:
  explicit IpoptRelaxationSolver(const IpoptSettings& settings) : app_(IpoptApplicationFactory()), max_cpu_time_s_(settings.max_cpu_time_s) {
    // Initialise from an empty stream: an ipopt.opt file in the working directory must
    // not change the planner's behaviour.
    std::istringstream no_options_file;
    MFP_CHECK_MSG(app_->Initialize(no_options_file) == Ipopt::Solve_Succeeded, "Ipopt failed to initialise");
    Ipopt::OptionsList& o = *app_->Options();
    o.SetIntegerValue("print_level", 0);
    o.SetStringValue("sb", "yes");  // no banner
    o.SetNumericValue("tol", settings.tolerance);
    o.SetIntegerValue("max_iter", settings.max_iterations);
    o.SetNumericValue("max_cpu_time", settings.max_cpu_time_s);
    o.SetStringValue("hessian_constant", "yes");
    o.SetStringValue("jac_c_constant", "yes");
    o.SetStringValue("jac_d_constant", "yes");
    o.SetStringValue("linear_solver", settings.linear_solver);
    // Fixed variables (integers fixed by branching) are removed from the problem.
    o.SetStringValue("fixed_variable_treatment", "make_parameter");
    if (settings.mehrotra) {
      o.SetStringValue("mehrotra_algorithm", "yes");
    } else {
      o.SetStringValue("mu_strategy", "adaptive");
    }
  }

  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    // Ipopt sees only the free variables and the rows that still constrain them.
    const Eigen::VectorXd& lower = request.LowerOr(problem);
    const Eigen::VectorXd& upper = request.UpperOr(problem);
    const Eigen::VectorXd* warm_start = request.WarmStart();
    const Deadline& deadline = request.deadline;
    RelaxationResult result;
    ReducedQp reduced;
    if (ReduceOrSettle(problem, lower, upper, kRowTolerance, &reduced, &result)) return result;
    Eigen::VectorXd reduced_start;
    if (warm_start != nullptr) reduced_start = reduced.Restrict(*warm_start);
    // Debian's Ipopt factorises with sequential MUMPS, which keeps global state: one
    // Ipopt solve at a time in the process, whichever solver object runs it.
    static std::mutex ipopt_mutex;
    const std::lock_guard<std::mutex> lock(ipopt_mutex);
    if (deadline.Expired()) {
      result.status = RelaxationStatus::kIterationLimit;
      result.x = Eigen::VectorXd::Zero(problem.num_variables());
      return result;
    }
    // Ipopt's own limit counts CPU time: at most what is left of the deadline (the
    // callback holds the deadline itself, on wall time).
    app_->Options()->SetNumericValue("max_cpu_time",
                                     std::clamp(deadline.RemainingSeconds(), 1e-3, max_cpu_time_s_));
    Ipopt::SmartPtr<QpTnlp> tnlp = new QpTnlp(reduced.problem, reduced.lower, reduced.upper,
                                              warm_start != nullptr ? &reduced_start : nullptr, deadline);
    Ipopt::ApplicationReturnStatus status = app_->OptimizeTNLP(Ipopt::GetRawPtr(tnlp));
    Miqp widened;  // outlives the retry's TNLP, which refers to it
    if (status == Ipopt::Not_Enough_Degrees_Of_Freedom) {
      // Ipopt refuses more equality rows than free variables (deep nodes have few free
      // variables). Give each equality a slab of width kRowTolerance instead.
      widened = reduced.problem;
      for (int i = 0; i < widened.num_rows(); ++i) {
        if (widened.row_lower(i) == widened.row_upper(i)) {
          widened.row_lower(i) -= 0.5 * kRowTolerance;
          widened.row_upper(i) += 0.5 * kRowTolerance;
        }
      }
      tnlp = new QpTnlp(widened, reduced.lower, reduced.upper, warm_start != nullptr ? &reduced_start : nullptr,
                        deadline);
      status = app_->OptimizeTNLP(Ipopt::GetRawPtr(tnlp));
    }
    const Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app_->Statistics();
    if (Ipopt::IsValid(stats)) result.iterations = stats->IterationCount();
    if (tnlp->x().size() != static_cast<Eigen::Index>(reduced.free_index.size())) {
      result.status = RelaxationStatus::kFailed;
      result.x = Eigen::VectorXd::Zero(problem.num_variables());
      return result;
    }
    result.x = reduced.Expand(tnlp->x());
    result.objective = problem.Objective(result.x);
    switch (status) {
      case Ipopt::Solve_Succeeded:
      case Ipopt::Solved_To_Acceptable_Level:
        result.status = RelaxationStatus::kSolved;
        break;
      case Ipopt::Infeasible_Problem_Detected:
      case Ipopt::Restoration_Failed:
        // The problem is convex, so a point of local infeasibility proves infeasibility;
        // a failure at a feasible point proves nothing.
        result.status = reduced.problem.MaxViolationOfRows(tnlp->x()) > kRowTolerance
                            ? RelaxationStatus::kInfeasible
                            : RelaxationStatus::kFailed;
        break;
      case Ipopt::Maximum_Iterations_Exceeded:
      case Ipopt::Maximum_CpuTime_Exceeded:
      case Ipopt::User_Requested_Stop:  // the deadline (intermediate_callback)
        result.status = RelaxationStatus::kIterationLimit;
        break;
      default:
        result.status = RelaxationStatus::kFailed;
        break;
    }
    return result;
  }

  std::string Name() const override { return "ipopt"; }

 private:
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  double max_cpu_time_s_;  // the most any one solve may take, in CPU seconds
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeIpoptRelaxationSolver(const IpoptSettings& settings) {
  return std::make_unique<IpoptRelaxationSolver>(settings);
}

}  // namespace mfp
