#include "planner/qp/internal/fallback_relaxation_solver.h"

#include <chrono>
#include <utility>

namespace mfp {
namespace {

class FallbackRelaxationSolver final : public RelaxationSolver {
 public:
  FallbackRelaxationSolver(std::unique_ptr<RelaxationSolver> primary, std::unique_ptr<RelaxationSolver> fallback)
      : primary_(std::move(primary)), fallback_(std::move(fallback)) {}

  // The fallback solves to the end: it gets the request without its cutoff.
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    const auto start = std::chrono::steady_clock::now();
    RelaxationResult result = primary_->Solve(problem, request);
    if (result.status == RelaxationStatus::kSolved || result.status == RelaxationStatus::kInfeasible ||
        result.status == RelaxationStatus::kCutoff || request.deadline.Expired() || result.over_work_budget) {
      return result;
    }
    RelaxationRequest to_the_end = request;
    to_the_end.cutoff = kInfinity;
    to_the_end.relative_tolerance = 0.0;
    RelaxationResult fallback = fallback_->Solve(problem, to_the_end);
    fallback.fallbacks += 1;
    fallback.fallback_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return fallback;
  }

  std::string Name() const override { return primary_->Name() + "+" + fallback_->Name(); }

 private:
  std::unique_ptr<RelaxationSolver> primary_;
  std::unique_ptr<RelaxationSolver> fallback_;
};

}  // namespace

std::unique_ptr<RelaxationSolver> MakeFallbackRelaxationSolver(std::unique_ptr<RelaxationSolver> primary,
                                                               std::unique_ptr<RelaxationSolver> fallback) {
  return std::make_unique<FallbackRelaxationSolver>(std::move(primary), std::move(fallback));
}

}  // namespace mfp
